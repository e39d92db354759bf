//! Edge flips towards the largest smallest angle, judged on the surface triangles (ours; the
//! paper keeps the cap grid's connectivity, Sec. 4.2).
//!
//! An edge is flipped when the smallest 3-D angle of its two faces grows, the flipped pair is
//! positively oriented in the mesh's chart (the map's plane, or the cap for a closed surface:
//! the mesh stays an embedding, so every later lift lands on the right sheet), no edge is
//! doubled, and neither the old nor the new pair is bent by more than the crease bound
//! (creases of the input are kept). Each accepted flip
//! raises the pair's smallest angle, so a pass cannot cycle; passes repeat until none flips.

use super::state::{edge_faces, smallest_angle_tan, third, Shaping};
use crate::mesh::fasthash::FastMap;
use crate::mesh::geometry::{cross, dot, norm, sub};
use rayon::prelude::*;

/// Smallest gain of the pair's smallest angle (radians) for a flip: ties are not flipped back
/// and forth.
const MIN_GAIN: f64 = 1e-6;

/// Planar area a flipped face must keep, relative to the pair's planar area.
const MIN_PLANAR_SHARE: f64 = 1e-6;

/// Passes at most in one call (the first over every edge, the others over the edges of the
/// pairs flipped in the pass before).
const MAX_PASSES: usize = 8;

/// Flip edges of `mesh` until no flip raises a pair's smallest angle (at most
/// [`MAX_PASSES`] passes); `crease` is the largest angle (radians) between the normals of the
/// two faces, before and after, of a flipped edge. The spokes and ring of a closed surface's
/// bottom fan are flipped here too ([`FanFlip`]): not in the iterations, where a spoke flipped
/// early could strand a ring vertex next to the centre (docs/method.md, "Remesh shape").
/// Returns the number of flips.
pub(crate) fn flip_to_max_min_angle(mesh: &mut Shaping, crease: f64) -> usize {
    let mut flipper = Flipper::new(mesh, crease);
    flipper.fans = fans(mesh);
    flipper.run(mesh, Criterion::MinAngle)
}

/// A relaxation or polish iteration's flips with `flipper` (its edge table kept from the last
/// iteration unless the faces changed otherwise): when `valence`, first flip edges while a
/// flip brings the valences of its four vertices closer to the regular ones (6 inside, 4 on
/// the boundary) without making the pair's smallest angle fall below [`VALENCE_FLOOR_DEG`] or
/// below what it was (as in isotropic remeshing, Botsch and Kobbelt 2004; the sum of squared
/// valence excesses falls with every flip, so a pass cannot cycle), then the flips of
/// [`flip_to_max_min_angle`] that do not move the valences away from the regular ones unless
/// the pair's smallest angle is below the floor (otherwise they undid about as many valence
/// flips in every relaxation iteration: docs/method.md section 18, "Flips that keep the
/// valences"); without `valence`, the flips of [`flip_to_max_min_angle`]. Returns the number
/// of flips.
pub(crate) fn flip_valence_then_angle(flipper: &mut Flipper, mesh: &mut Shaping, valence: bool) -> usize {
    let by_valence = if valence { flipper.run(mesh, Criterion::Valence) } else { 0 };
    by_valence + flipper.run(mesh, if valence { Criterion::MinAngleKeepingValence } else { Criterion::MinAngle })
}

/// Smallest angle (degrees) a valence flip may leave in its pair (unless it was smaller).
pub(crate) const VALENCE_FLOOR_DEG: f64 = 25.0;

/// What a flip does to a fan (a closed surface's bottom vertex, which has no planar point,
/// and its neighbours, [`super::bottom`]).
#[derive(Clone, Copy, PartialEq, Debug)]
enum FanFlip {
    /// No fan is involved.
    No,
    /// A spoke of the fan centred at this vertex is flipped away: the fan loses a neighbour.
    Remove(u32),
    /// An edge of the fan's ring is flipped to a spoke of the fan centred at this vertex.
    Insert(u32),
}

/// The planar test of a flip ([`improves`]) by what it does to a fan.
enum Fan<'a> {
    /// Both new faces are planar.
    No,
    /// The centre and its neighbours: only the new face without the centre is planar.
    Remove(u32, &'a [u32]),
    /// Both new faces hold the centre: none is planar.
    Insert,
}

/// An edge's verdict judged at the start of a pass, on the mesh as it was then.
#[derive(Clone, Copy)]
struct Ahead {
    /// The pair's opposite corners when it is an interior pair of planar faces without a fan
    /// (`None` otherwise: judged again in the sweep).
    corners: Option<[u32; 2]>,
    /// Whether flipping it improves what the pass asks for (`false` without `corners`: the
    /// sweep never reads it then).
    better: bool,
}

/// What a flip must improve.
#[derive(Clone, Copy, PartialEq)]
enum Criterion {
    MinAngle,
    /// A larger smallest angle without a larger valence excess, unless the pair's smallest
    /// angle is below [`VALENCE_FLOOR_DEG`].
    MinAngleKeepingValence,
    Valence,
}

/// The flips' bookkeeping, kept up to date across flips; [`Flipper::refresh`] after vertex
/// moves, a new one after any other change of the faces.
pub(crate) struct Flipper {
    /// Each undirected edge: its two faces (the one where it runs a -> b, then b -> a).
    edges: FastMap<(u32, u32), [u32; 2]>,
    /// Faces at each vertex.
    valence: Vec<i32>,
    /// Regular face count at each vertex: 6 inside, 3 on the boundary.
    regular: Vec<i32>,
    /// Tangent of each face's smallest angle ([`smallest_angle_tan`]).
    face_tan: Vec<f64>,
    cos_crease: f64,
    /// The neighbours of each vertex without a planar point whose neighbours all have one (a
    /// closed surface's bottom vertex, [`super::bottom`]): its spokes may be flipped.
    fans: FastMap<u32, Vec<u32>>,
}

impl Flipper {
    /// The bookkeeping of `mesh`'s faces; `crease` as in [`flip_to_max_min_angle`].
    pub(crate) fn new(mesh: &Shaping, crease: f64) -> Self {
        let n = mesh.plane.len();
        let mut valence = vec![0i32; n];
        for f in &mesh.faces {
            for &v in f {
                valence[v as usize] += 1;
            }
        }
        let edges = edge_faces(&mesh.faces);
        // Regular valence: 6 inside, 4 on the boundary (a boundary vertex has one face fewer
        // than neighbours, so count faces: 6 inside, 3 on the boundary).
        let mut regular = vec![6i32; n];
        for (&(a, b), f) in &edges {
            if f[0] == u32::MAX || f[1] == u32::MAX {
                regular[a as usize] = 3;
                regular[b as usize] = 3;
            }
        }
        let face_tan = mesh.faces.iter().map(|f| face_tan(mesh, *f)).collect();
        Self { edges, valence, regular, face_tan, cos_crease: crease.cos(), fans: Default::default() }
    }

    /// Whether flipping `(a, b)` (opposite corners `c`, `d`) changes a fan
    /// ([`FanFlip`]); `None` when it does not and some of the four vertices has no planar
    /// point (no flip).
    fn fan_flip(&self, mesh: &Shaping, [a, b, c, d]: [u32; 4]) -> Option<FanFlip> {
        let fan = |v: u32| !mesh.planar(v) && self.fans.contains_key(&v);
        match [a, b, c, d].map(|v| mesh.planar(v)) {
            [true, true, true, true] => Some(FanFlip::No),
            [false, true, true, true] if fan(a) => Some(FanFlip::Remove(a)),
            [true, false, true, true] if fan(b) => Some(FanFlip::Remove(b)),
            [true, true, false, true] if fan(c) => Some(FanFlip::Insert(c)),
            [true, true, true, false] if fan(d) => Some(FanFlip::Insert(d)),
            _ => None,
        }
    }

    /// Take the vertices' new positions (the faces unchanged since the last flips).
    pub(crate) fn refresh(&mut self, mesh: &Shaping) {
        self.face_tan.par_iter_mut().zip(mesh.faces.par_iter()).for_each(|(t, f)| *t = face_tan(mesh, *f));
    }

    /// Passes of flips by `criterion` until none flips ([`MAX_PASSES`] at most).
    fn run(&mut self, mesh: &mut Shaping, criterion: Criterion) -> usize {
        let mut interior: Vec<((u32, u32), [u32; 2])> = self.edges.iter().filter(|(_, f)| f[0] != u32::MAX && f[1] != u32::MAX).map(|(&k, &f)| (k, f)).collect();
        interior.sort_unstable_by_key(|&(k, _)| k);
        let mut keys: Vec<(u32, u32)> = interior.iter().map(|&(k, _)| k).collect();
        // The first pass visits every edge: its verdicts are judged in parallel on the mesh
        // as it is before the pass. A verdict depends only on the pair's two faces and its
        // four vertices' positions and valences, which no earlier flip of the pass changed
        // when none of the four vertices took part in one (a flip changes only faces whose
        // corners are its own four vertices): then the verdict judged ahead is the one the
        // sweep would judge, and the flips are those of a sequential pass.
        // Most edges keep their verdict `false` through the pass: those whose four vertices no
        // flip touched are skipped without looking them up again.
        let ahead: Vec<Ahead> = {
            let this = &*self;
            let mesh = &*mesh;
            interior
                .par_iter()
                .map(|&((a, b), faces)| match pair_of(mesh, a, b, faces) {
                    Some((t1, t2, c, d)) if this.fan_flip(mesh, [a, b, c, d]) == Some(FanFlip::No) => Ahead { corners: Some([c, d]), better: this.better(mesh, criterion, [a, b, c, d], [t1, t2], FanFlip::No) },
                    // A spoke is judged afresh in the sweep, and an edge without a pair or
                    // with an unplanar corner stays so while its vertices are untouched.
                    _ => Ahead { corners: None, better: false },
                })
                .collect()
        };
        let mut touched = vec![false; mesh.plane.len()];
        let mut flips = 0;
        let mut changed: Vec<(u32, u32)> = Vec::new();
        for pass in 0..MAX_PASSES {
            let mut this_pass = 0;
            for (i, &(a, b)) in keys.iter().enumerate() {
                if pass == 0 {
                    if let Ahead { corners: Some([c, d]), better: false } = ahead[i] {
                        if [a, b, c, d].iter().all(|&v| !touched[v as usize]) {
                            continue;
                        }
                    }
                }
                let Some((t1, t2, c, d)) = self.pair(mesh, a, b) else { continue };
                let Some(fan_flip) = self.fan_flip(mesh, [a, b, c, d]) else { continue };
                if c == d || self.edges.contains_key(&(c.min(d), c.max(d))) {
                    continue;
                }
                // A spoke's verdict also depends on the fan's other vertices, which other
                // spoke flips of the pass change: it is judged afresh.
                let judged_ahead = pass == 0 && fan_flip == FanFlip::No && [a, b, c, d].iter().all(|&v| !touched[v as usize]);
                let better = if judged_ahead { ahead[i].better } else { self.better(mesh, criterion, [a, b, c, d], [t1, t2], fan_flip) };
                if !better {
                    continue;
                }
                if pass == 0 {
                    for v in [a, b, c, d] {
                        touched[v as usize] = true;
                    }
                }
                match fan_flip {
                    // The spoke's other end leaves the fan; the opposite corner joins it.
                    FanFlip::Remove(o) => {
                        let apex = if o == a { b } else { a };
                        if let Some(fan) = self.fans.get_mut(&o) {
                            fan.retain(|&v| v != apex);
                        }
                    }
                    FanFlip::Insert(o) => {
                        let apex = if o == c { d } else { c };
                        if let Some(fan) = self.fans.get_mut(&o) {
                            fan.push(apex);
                        }
                    }
                    FanFlip::No => {}
                }
                self.valence[a as usize] -= 1;
                self.valence[b as usize] -= 1;
                self.valence[c as usize] += 1;
                self.valence[d as usize] += 1;
                // New faces (c, a, d) and (d, b, c), replacing t1 and t2.
                mesh.faces[t1 as usize] = [c, a, d];
                mesh.faces[t2 as usize] = [d, b, c];
                self.face_tan[t1 as usize] = face_tan(mesh, [c, a, d]);
                self.face_tan[t2 as usize] = face_tan(mesh, [d, b, c]);
                self.edges.remove(&(a, b));
                // t2 = (d, b, c) runs c -> d, t1 = (c, a, d) runs d -> c.
                self.edges.insert((c.min(d), c.max(d)), if c < d { [t2, t1] } else { [t1, t2] });
                // Edge (b, c) moved from t1 to t2, edge (a, d) from t2 to t1.
                reassign(&mut self.edges, b, c, t1, t2);
                reassign(&mut self.edges, a, d, t2, t1);
                this_pass += 1;
                // The next pass visits the edges of the flipped pairs only: an angle verdict
                // depends on the pair alone (a valence verdict also on the four valences, whose
                // other edges wait for the next call).
                for (u, v) in [(a, c), (c, b), (b, d), (d, a), (c, d)] {
                    changed.push((u.min(v), u.max(v)));
                }
            }
            flips += this_pass;
            if this_pass == 0 {
                break;
            }
            keys = std::mem::take(&mut changed);
            keys.sort_unstable();
            keys.dedup();
        }
        flips
    }

    /// The faces `(t1, t2)` of interior edge `(a, b)` (`t1 = (a, b, c)`, `t2 = (b, a, d)`) and
    /// its opposite corners `c`, `d`; `None` on the boundary.
    fn pair(&self, mesh: &Shaping, a: u32, b: u32) -> Option<(u32, u32, u32, u32)> {
        pair_of(mesh, a, b, *self.edges.get(&(a, b))?)
    }

    /// The sum of the squared valence excesses of the four vertices of edge `(a, b)` and its
    /// opposite corners `c`, `d`, before and after the edge's flip.
    fn valence_excess(&self, [a, b, c, d]: [u32; 4]) -> (i32, i32) {
        let dev = |v: u32, change: i32| {
            let e = self.valence[v as usize] + change - self.regular[v as usize];
            e * e
        };
        (dev(a, 0) + dev(b, 0) + dev(c, 0) + dev(d, 0), dev(a, -1) + dev(b, -1) + dev(c, 1) + dev(d, 1))
    }

    /// Whether flipping the edge `(a, b)` of the pair `[t1, t2]` with opposite corners `c`,
    /// `d` improves what `criterion` asks for (the edge's existence and planarity checked
    /// by the caller).
    fn better(&self, mesh: &Shaping, criterion: Criterion, [a, b, c, d]: [u32; 4], [t1, t2]: [u32; 2], fan_flip: FanFlip) -> bool {
        let old = self.face_tan[t1 as usize].min(self.face_tan[t2 as usize]);
        let fan = match fan_flip {
            FanFlip::Remove(o) => Fan::Remove(o, self.fans.get(&o).map_or(&[][..], |f| &f[..])),
            FanFlip::Insert(_) => Fan::Insert,
            FanFlip::No => Fan::No,
        };
        match criterion {
            Criterion::MinAngle => improves(mesh, [a, b, c, d], old, self.cos_crease, None, fan),
            Criterion::MinAngleKeepingValence => {
                let (before, after) = self.valence_excess([a, b, c, d]);
                (after <= before || old < VALENCE_FLOOR_DEG.to_radians().tan()) && improves(mesh, [a, b, c, d], old, self.cos_crease, None, fan)
            }
            Criterion::Valence => {
                let (before, after) = self.valence_excess([a, b, c, d]);
                after < before && improves(mesh, [a, b, c, d], old, self.cos_crease, Some(VALENCE_FLOOR_DEG.to_radians().tan()), fan)
            }
        }
    }
}

/// [`Flipper::pair`] of edge `(a, b)` whose faces (where it runs a -> b, then b -> a) are
/// `[t1, t2]`.
fn pair_of(mesh: &Shaping, a: u32, b: u32, [t1, t2]: [u32; 2]) -> Option<(u32, u32, u32, u32)> {
    if t1 == u32::MAX || t2 == u32::MAX {
        return None;
    }
    let c = third(mesh.faces[t1 as usize], a, b)?;
    let d = third(mesh.faces[t2 as usize], b, a)?;
    Some((t1, t2, c, d))
}

/// [`smallest_angle_tan`] of face `f` of `mesh`.
fn face_tan(mesh: &Shaping, f: [u32; 3]) -> f64 {
    let [a, b, c] = f.map(|v| mesh.position[v as usize]);
    smallest_angle_tan(a, b, c)
}

/// Replace face `from` by `to` among the faces of edge `(u, v)`.
fn reassign(edges: &mut FastMap<(u32, u32), [u32; 2]>, u: u32, v: u32, from: u32, to: u32) {
    if let Some(slot) = edges.get_mut(&(u.min(v), u.max(v))) {
        for t in slot.iter_mut() {
            if *t == from {
                *t = to;
            }
        }
    }
}

/// Each fan's centre (a vertex without a planar point whose neighbours all have one) and its
/// neighbours.
fn fans(mesh: &Shaping) -> FastMap<u32, Vec<u32>> {
    let mut fans: FastMap<u32, Vec<u32>> = Default::default();
    for f in &mesh.faces {
        for k in 0..3 {
            if !mesh.planar(f[k]) {
                fans.entry(f[k]).or_default().extend([f[(k + 1) % 3], f[(k + 2) % 3]]);
            }
        }
    }
    fans.retain(|_, ring| ring.iter().all(|&v| mesh.planar(v)));
    for ring in fans.values_mut() {
        ring.sort_unstable();
        ring.dedup();
    }
    fans
}

/// Whether flipping edge `(a, b)` of faces `(a, b, c)`, `(b, a, d)` to `(c, a, d)`, `(d, b, c)`
/// raises the smallest 3-D angle, whose tangent is `old_tan` before the flip (or, with a
/// `floor_tan`, leaves its tangent at least at the floor's or at the old one), keeps the planar
/// orientation and stays within the crease bound. A face with a fan's centre is judged on the
/// surface only (as the centre's moves are): when a spoke is flipped away
/// ([`Fan::Remove`]), the new face without the centre must be oriented and hold no other
/// vertex of the fan, so that the fan's ring stays a simple polygon in the plane.
fn improves(mesh: &Shaping, [a, b, c, d]: [u32; 4], old_tan: f64, cos_crease: f64, floor_tan: Option<f64>, fan: Fan) -> bool {
    let x = |v: u32| mesh.position[v as usize];
    let p = |v: u32| mesh.plane[v as usize];
    let new_tan = smallest_angle_tan(x(c), x(a), x(d)).min(smallest_angle_tan(x(d), x(b), x(c)));
    let enough = match floor_tan {
        // The angles themselves only for the few pairs that gain.
        None => new_tan > old_tan && new_tan.atan() > old_tan.atan() + MIN_GAIN,
        Some(floor) => new_tan >= old_tan.min(floor),
    };
    if !enough {
        return false;
    }
    match fan {
        Fan::No => {
            let pair = mesh.chart.signed_area(p(a), p(b), p(c)).abs() + mesh.chart.signed_area(p(b), p(a), p(d)).abs();
            let floor = MIN_PLANAR_SHARE * pair;
            if !(mesh.oriented(p(c), p(a), p(d), floor) && mesh.oriented(p(d), p(b), p(c), floor)) {
                return false;
            }
        }
        Fan::Remove(o, ring) => {
            // The new planar face: (d, b, c) when the centre is a, (c, a, d) when it is b.
            let [x, y, z] = if o == a { [d, b, c] } else { [c, a, d] };
            let (px, py, pz) = (p(x), p(y), p(z));
            let scale = (py[0] - px[0]).hypot(py[1] - px[1]) * (pz[0] - px[0]).hypot(pz[1] - px[1]);
            if !mesh.oriented(px, py, pz, MIN_PLANAR_SHARE * scale) {
                return false;
            }
            let inside = |q: [f64; 2]| mesh.oriented(px, py, q, 0.0) && mesh.oriented(py, pz, q, 0.0) && mesh.oriented(pz, px, q, 0.0);
            if ring.iter().any(|&v| v != x && v != y && v != z && inside(p(v))) {
                return false;
            }
        }
        // Both new faces hold the centre: nothing is planar.
        Fan::Insert => {}
    }
    // Neither pair may bend by more than the crease bound; or the new pair bends less than
    // the old one when
    // that one is folded back beyond FOLD_DEG, which is a fold of the remesh (the surface
    // sampled too coarsely there, as across the tip of an ear), not a crease of the input.
    let (old_bend, new_bend) = (bend_cos(x(a), x(b), x(c), x(d)), bend_cos(x(c), x(d), x(b), x(a)));
    // A sliver's normal is not the surface's: a pair holding one next to a crease vertex
    // may be flipped into an unbent pair whatever its bend (three crease vertices nearly in
    // line, `super::crease`).
    let crease_sliver = old_tan < SLIVER_DEG.to_radians().tan() && [a, b, c, d].iter().any(|&v| mesh.role[v as usize] == super::state::Role::Crease);
    (old_bend >= cos_crease && new_bend >= cos_crease) || (old_bend < FOLD_DEG.to_radians().cos() && new_bend > old_bend) || (crease_sliver && new_bend >= cos_crease)
}

/// A face whose smallest angle is below this (degrees) is a sliver for the crease bound.
const SLIVER_DEG: f64 = 5.0;

/// A pair of faces bent by more than this (degrees) is a fold of the remesh, not a crease.
const FOLD_DEG: f64 = 120.0;

/// Cosine of the angle between the normals of `(a, b, c)` and `(b, a, d)`: 1 when flat, -1
/// when folded back (1 for a degenerate face, which the angle test has already judged).
pub(crate) fn bend_cos(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]) -> f64 {
    let n1 = cross(sub(b, a), sub(c, a));
    let n2 = cross(sub(a, b), sub(d, b));
    let l = norm(n1) * norm(n2);
    if l > 0.0 { dot(n1, n2) / l } else { 1.0 }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::remesh::shape::state::Role;

    fn quad(z_d: f64) -> Shaping {
        // Quad a=(0,0), b=(4,0.2)... split along the long diagonal a-b: two flat slivers.
        let plane = vec![[0.0, 0.0], [4.0, 0.0], [2.0, 0.5], [2.0, -0.5]];
        let position = vec![[0.0, 0.0, 0.0], [4.0, 0.0, 0.0], [2.0, 0.5, 0.0], [2.0, -0.5, z_d]];
        Shaping { faces: vec![[0, 1, 2], [1, 0, 3]], plane, position, hint: vec![u32::MAX; 4], role: vec![Role::Free; 4], has_plane: vec![true; 4], orientation: 1.0, chart: crate::remesh::shape::state::Chart::Plane }
    }

    #[test]
    fn a_sliver_pair_is_flipped_to_the_short_diagonal() {
        let mut mesh = quad(0.0);
        assert_eq!(flip_to_max_min_angle(&mut mesh, 60f64.to_radians()), 1);
        let mut edges: Vec<[u32; 2]> = mesh.faces.iter().flat_map(|f| (0..3).map(move |k| { let (a, b) = (f[k], f[(k + 1) % 3]); [a.min(b), a.max(b)] })).collect();
        edges.sort_unstable();
        assert!(edges.contains(&[2, 3]) && !edges.contains(&[0, 1]), "{:?}", mesh.faces);
        // Both faces keep the planar orientation.
        for f in &mesh.faces {
            let [a, b, c] = f.map(|v| mesh.plane[v as usize]);
            assert!(crate::mesh::geometry::signed_area_2d(a, b, c) > 0.0);
        }
        // Flipping again would lower the smallest angle: nothing more happens.
        assert_eq!(flip_to_max_min_angle(&mut mesh, 60f64.to_radians()), 0);
    }

    /// A closed surface's bottom vertex (no planar point) with a spoke to a ring vertex next
    /// to it: the final flips turn the spoke into an edge of the ring (judged on the surface;
    /// the new planar face keeps the plane's orientation).
    #[test]
    fn a_short_spoke_of_the_bottom_fan_is_flipped_away() {
        // m inside, ring r0..r3 (r0 dented inside the chord r1-r3 in the plane), bottom o.
        let (m, r0, r1, r2, r3, o) = (0u32, 1u32, 2u32, 3u32, 4u32, 5u32);
        let plane = vec![[0.0, 0.0], [0.4, 0.0], [0.5, 0.866], [-1.0, 0.0], [0.5, -0.866], [0.0, 0.0]];
        let position = vec![[0.1, 0.0, 0.8], [0.0, 0.0, 0.0], [0.5, 0.866, 0.0], [-1.0, 0.0, 0.0], [0.5, -0.866, 0.0], [0.0, 0.0, -0.1]];
        let faces = vec![[m, r0, r1], [m, r1, r2], [m, r2, r3], [m, r3, r0], [o, r1, r0], [o, r2, r1], [o, r3, r2], [o, r0, r3]];
        let mut role = vec![Role::Free; 6];
        role[o as usize] = Role::Fixed;
        let mut has_plane = vec![true; 6];
        has_plane[o as usize] = false;
        let mut mesh = Shaping { faces, plane, position, hint: vec![u32::MAX; 6], role, has_plane, orientation: 1.0, chart: crate::remesh::shape::state::Chart::Plane };
        let smallest = |mesh: &Shaping| mesh.faces.iter().map(|f| face_tan(mesh, *f).atan()).fold(f64::INFINITY, f64::min);
        let before = smallest(&mesh);
        assert!(flip_to_max_min_angle(&mut mesh, 170f64.to_radians()) >= 1);
        assert!(!mesh.faces.iter().any(|f| f.contains(&o) && f.contains(&r0)), "{:?}", mesh.faces);
        assert!(smallest(&mesh) > before + 0.1, "smallest angle {} from {before}", smallest(&mesh));
        for f in mesh.faces.iter().filter(|f| !f.contains(&o)) {
            let [a, b, c] = f.map(|v| mesh.plane[v as usize]);
            assert!(crate::mesh::geometry::signed_area_2d(a, b, c) > 0.0, "{f:?}");
        }
        // The fan still closes the surface: every edge in two faces.
        let edges = edge_faces(&mesh.faces);
        assert!(edges.values().all(|t| t[0] != u32::MAX && t[1] != u32::MAX));
    }

    #[test]
    fn a_crease_is_kept() {
        // d lifted far out of the plane: the flipped pair would bend by about 80 degrees.
        let mut mesh = quad(3.0);
        let before = mesh.faces.clone();
        flip_to_max_min_angle(&mut mesh, 30f64.to_radians());
        assert_eq!(mesh.faces, before);
    }
}
