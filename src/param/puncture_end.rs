//! Which end of a closed surface's principal axis is punctured (paper Sec. 3.2.1 punctures
//! "the bottom"), and [`super::PunctureEnd::Best`]: the radius search from both ends in parallel,
//! then the rest of the parameterization for the end whose search map is the more
//! area-preserving.

use super::finish::{finish, parameterize_once};
use super::options::ParamOptions;
use super::prepare::Prepared;
use super::report::PunctureTrial;
use super::search::{search_radius, Searched};
use crate::cap::CapMap;
use crate::error::Error;
use crate::mesh::TriMesh;
use crate::progress::Progress;
use std::time::Instant;

/// [`super::parameterize`] of the prepared `mesh` with [`super::PunctureEnd::Best`]: `bottom` and
/// `top` are the options with the puncture at either end.
pub(crate) fn parameterize_best_end(mesh: &TriMesh, prepared: &Prepared, bottom: &ParamOptions, top: &ParamOptions, progress: &dyn Progress) -> Result<CapMap, Error> {
    let start = Instant::now();
    // Open surfaces have no puncture: one map. (So are inputs that are closed only once
    // welded, as before the preparation was shared.)
    if !prepared.input_closed {
        return parameterize_once(mesh, prepared, bottom, progress);
    }
    // Closed ones search both ends at once (independent; on two cores this halves the
    // wall time), then finish the end whose search map is the more area-preserving. While
    // both flatten, each solves its two right-hand sides in one pass (the cores are busy).
    let one_pass = |o: &ParamOptions| {
        let mut o = o.clone();
        o.closed.flatten.parallel_solves = false;
        o
    };
    let (first, second) = rayon::join(|| search_radius(prepared, &one_pass(bottom), true, progress), || search_radius(prepared, &one_pass(top), true, progress));
    let first = first?;
    let axis = |s: &Searched<'_>| s.puncture.as_ref().map_or([0.0; 3], |p| p.axis);
    let trial = |s: &Searched<'_>| PunctureTrial { axis: axis(s), search_area_distortion: s.search_area_distortion, mean_abs_area_distortion: None };
    let finished = |mut m: CapMap, trials: Vec<PunctureTrial>| {
        m.report.puncture_trials = trials;
        for t in &mut m.report.puncture_trials {
            if m.report.puncture.as_ref().is_some_and(|p| p.axis == t.axis) {
                t.mean_abs_area_distortion = Some(m.report.area_distortion.mean_abs);
            }
        }
        m.report.seconds = start.elapsed().as_secs_f64();
        m
    };
    let second = match second {
        Ok(s) => s,
        Err(e @ Error::Cancelled(_)) => return Err(e),
        // The other end could not be mapped (e.g. no regular quad there): keep this one.
        Err(_) => {
            let trials = vec![trial(&first)];
            return Ok(finished(finish(mesh, first, bottom, progress)?, trials));
        }
    };
    let trials = vec![trial(&first), trial(&second)];
    match (first.search_area_distortion, second.search_area_distortion) {
        (Some(a), Some(b)) => {
            // The other end's maps go before the kept end's second half.
            let (kept, options) = if b < a {
                drop(first);
                (second, top)
            } else {
                drop(second);
                (first, bottom)
            };
            Ok(finished(finish(mesh, kept, options, progress)?, trials))
        }
        // No search (a fixed domain): finish both and keep the better map.
        _ => {
            let (a, b) = rayon::join(|| finish(mesh, first, bottom, progress), || finish(mesh, second, top, progress));
            let (a, b) = (a?, b?);
            let key = |m: &CapMap| (m.report.flipped_faces, m.report.area_distortion.mean_abs);
            let means = [a.report.area_distortion.mean_abs, b.report.area_distortion.mean_abs];
            let kept = if key(&b) < key(&a) { b } else { a };
            let mut kept = finished(kept, trials);
            for (t, m) in kept.report.puncture_trials.iter_mut().zip(means) {
                t.mean_abs_area_distortion = Some(m);
            }
            Ok(kept)
        }
    }
}
