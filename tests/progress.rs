//! The progress trait: stages report monotone fractions in [0, 1], and a `Break` cancels the
//! pipeline with `Error::Cancelled` instead of finishing.

use capmesh::param::{parameterize, ParamOptions};
use capmesh::mesh::shapes::{spherical_cap, spherical_cap_sectors};
use capmesh::progress::Stage;
use capmesh::Error;
use std::ops::ControlFlow;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

#[test]
fn reports_cover_the_stages_and_stay_in_range() {
    let mesh = spherical_cap(0.3, 10, spherical_cap_sectors(0.3, 10));
    let seen = Mutex::new(Vec::new());
    let sink = |stage: Stage, fraction: f64, _msg: &str| {
        seen.lock().unwrap().push((stage, fraction));
        ControlFlow::Continue(())
    };
    parameterize(&mesh, &ParamOptions::default(), &sink).unwrap();
    let seen = seen.into_inner().unwrap();
    assert!(seen.iter().all(|(_, f)| (0.0..=1.0).contains(f)));
    for stage in [Stage::Validate, Stage::Flatten, Stage::RadiusSearch, Stage::Project] {
        assert!(seen.iter().any(|(s, _)| *s == stage), "no report for {stage:?}");
    }
}

#[test]
fn break_cancels_the_parameterization() {
    let mesh = spherical_cap(0.3, 10, spherical_cap_sectors(0.3, 10));
    let calls = AtomicUsize::new(0);
    let sink = |_: Stage, _: f64, _: &str| {
        if calls.fetch_add(1, Ordering::SeqCst) >= 3 {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    };
    let err = parameterize(&mesh, &ParamOptions::default(), &sink).unwrap_err();
    assert!(matches!(err, Error::Cancelled(_) | Error::Transport(capmesh::omt::OmtError::Cancelled(_))), "{err:?}");
    // It stopped soon after the break, not at the end.
    assert!(calls.load(Ordering::SeqCst) <= 5);
}

/// The pipeline runs on rayon's pool (its short parallel loops split in place), but a
/// front end's callback may only be safe on its own thread (MeshLab's drives a Qt progress
/// bar): every report of a closed surface's map, whose two puncture ends search in
/// parallel, and of a remesh arrives on the calling thread.
#[test]
fn reports_arrive_on_the_calling_thread() {
    let caller = std::thread::current().id();
    let elsewhere = AtomicUsize::new(0);
    let calls = AtomicUsize::new(0);
    let sink = |_: Stage, _: f64, _: &str| {
        calls.fetch_add(1, Ordering::SeqCst);
        if std::thread::current().id() != caller {
            elsewhere.fetch_add(1, Ordering::SeqCst);
        }
        ControlFlow::Continue(())
    };
    let sphere = capmesh::mesh::shapes::icosphere(3);
    parameterize(&sphere, &ParamOptions::default(), &sink).unwrap();
    let cap = spherical_cap(0.3, 10, spherical_cap_sectors(0.3, 10));
    capmesh::remesh::remesh(&cap, &capmesh::remesh::RemeshOptions::default(), &sink).unwrap();
    assert!(calls.load(Ordering::SeqCst) > 10);
    assert_eq!(elsewhere.load(Ordering::SeqCst), 0, "reports on another thread");
}
