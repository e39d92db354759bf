//! Edge splits and collapses towards a target edge length (ours; see [`super`]), as in
//! isotropic remeshing (Botsch and Kobbelt 2004): edges longer than 4/3 of the target are
//! split, edges shorter than 4/5 of it collapsed.
//!
//! A cap grid relaxed with its own connectivity keeps the grid's rows: where the map
//! stretches by less than `sqrt(3)` the stretched lattice is already Delaunay, so no flip
//! changes it and no relaxation can make it equilateral, since each row has too many or too
//! few vertices. Splits and collapses change the rows' counts. A new vertex is the lift of
//! the planar midpoint (or, on an open surface's boundary, of the boundary track's arc
//! midpoint), a collapse keeps the remaining vertex's planar point or moves it to the
//! midpoint, so every vertex stays on the surface; an operation is made only when every
//! changed face keeps its planar orientation and its side on the surface, and a collapse
//! also only when it creates no edge longer than the split length. Neither is made where the
//! inverse map is not resolved at the edge's scale (the edge stretched more than
//! [`MAX_STRETCH`] times against the map's mean scale, or a split's lifted midpoint far from
//! the chord): there (the hand's finger webs, the bunny's ears) they left slivers. An open
//! surface's boundary edges shorter than half the target are collapsed along the input's
//! boundary ([`collapse_short_boundary_edges`]).

use super::boundary::Track;
use super::state::{drop_faces, edge_faces, neighbours, smallest_angle, third, Incidence, Role, Shaping, SurfaceLift};
use crate::mesh::geometry::{cross, dot, norm, signed_area_2d, sub};

/// Edges longer than this many target lengths are split.
pub(crate) const SPLIT: f64 = 4.0 / 3.0;
/// Edges shorter than this many target lengths are collapsed.
pub(crate) const COLLAPSE: f64 = 4.0 / 5.0;

/// Boundary edges shorter than this many target lengths are collapsed
/// ([`collapse_short_boundary_edges`]): fewer than the interior's [`COLLAPSE`], since a rim
/// that is a little dense is better left as the cap grid made it (at 4/5 the bundled hand
/// lost 0.35 degrees of mean smallest angle); a nearly closed surface's rim is 0.1-0.2.
pub(crate) const BOUNDARY_COLLAPSE: f64 = 0.5;

/// Cosine of the largest turn of a face's normal in a collapse (45 degrees): a collapse
/// that tilts a face more folds the surface where it is curved at the edge's scale.
const MAX_TURN_COS: f64 = std::f64::consts::FRAC_1_SQRT_2;

/// Largest distance, in edge lengths, between a split's new vertex and its edge's
/// midpoint: farther, the planar edge crosses a part of the surface the map compresses
/// below the remesh's scale.
const MAX_LIFT_OFFSET: f64 = 0.25;

/// Smallest angle (degrees) a collapse may leave in a face, unless the face had a smaller
/// one before.
const COLLAPSE_MIN_ANGLE_DEG: f64 = 25.0;

/// Most neighbours a collapse may leave a vertex with (two fewer on the boundary).
const MAX_VALENCE: usize = 8;

fn length(mesh: &Shaping, a: u32, b: u32) -> f64 {
    norm(sub(mesh.position[a as usize], mesh.position[b as usize]))
}

/// Largest stretch of an edge by the inverse map, against the map's mean scale, at which the
/// edge is split or collapsed: beyond it the map is far from area-preserving at the remesh's
/// scale (a fold, a finger's web) and moving vertices there makes slivers.
const MAX_STRETCH: f64 = 3.0;

/// The inverse map's mean length scale: the square root of surface area over planar area.
fn mean_scale(mesh: &Shaping) -> f64 {
    let (mut a3, mut a2) = (0.0, 0.0);
    for f in mesh.faces.iter().filter(|f| f.iter().all(|&v| mesh.planar(v))) {
        let y = f.map(|v| mesh.position[v as usize]);
        let p = f.map(|v| mesh.plane[v as usize]);
        a3 += 0.5 * norm(cross(sub(y[1], y[0]), sub(y[2], y[0])));
        a2 += 0.5 * signed_area_2d(p[0], p[1], p[2]).abs();
    }
    if a2 > 0.0 { (a3 / a2).sqrt() } else { 0.0 }
}

/// Whether the inverse map stretches edge `(a, b)` by no more than [`MAX_STRETCH`] either way.
fn resolved(mesh: &Shaping, scale: f64, a: u32, b: u32) -> bool {
    let (pa, pb) = (mesh.plane[a as usize], mesh.plane[b as usize]);
    let planar = ((pa[0] - pb[0]).powi(2) + (pa[1] - pb[1]).powi(2)).sqrt() * scale;
    let l = length(mesh, a, b);
    l <= MAX_STRETCH * planar && planar <= MAX_STRETCH * l
}

/// The arc length midway between arc lengths `sa` and `sb` on the closed `track`, the shorter
/// way round.
fn arc_midpoint(track: &Track, sa: f64, sb: f64) -> f64 {
    let len = track.length();
    let mut gap = (sb - sa).rem_euclid(len);
    if gap > 0.5 * len {
        gap -= len;
    }
    (sa + 0.5 * gap).rem_euclid(len)
}

/// Add a vertex; returns its number.
fn push_vertex(mesh: &mut Shaping, arc: &mut Vec<f64>, q: [f64; 2], x: [f64; 3], hint: u32, role: Role, s: f64) -> u32 {
    mesh.plane.push(q);
    mesh.position.push(x);
    mesh.hint.push(hint);
    mesh.role.push(role);
    mesh.has_plane.push(true);
    arc.push(s);
    (mesh.plane.len() - 1) as u32
}

/// Split the edges longer than `max_len` times `local(a, b)` (the sizing's length factor at
/// the edge), longest first, no two in one face per call. Returns the number of splits.
pub(crate) fn split_long_edges(mesh: &mut Shaping, track: Option<&Track>, arc: &mut Vec<f64>, lift: &SurfaceLift, max_len: f64, local: &dyn Fn(u32, u32) -> f64) -> usize {
    split_edges(mesh, track, arc, lift, &|a, b, l| (l > max_len * local(a, b)).then_some(-l), usize::MAX)
}

/// Split at most `limit` of the edges `(a, b)` (length `l`) for which `pick(a, b, l)` gives a
/// key, smallest key first, no two in one face per call, with the checks of
/// [`split_long_edges`]. Returns the number of splits.
pub(crate) fn split_edges(mesh: &mut Shaping, track: Option<&Track>, arc: &mut Vec<f64>, lift: &SurfaceLift, pick: &dyn Fn(u32, u32, f64) -> Option<f64>, limit: usize) -> usize {
    let edges = edge_faces(&mesh.faces);
    let scale = mean_scale(mesh);
    let mut long: Vec<(f64, (u32, u32), [u32; 2])> = edges
        .iter()
        .filter(|(&(a, b), _)| mesh.planar(a) && mesh.planar(b) && resolved(mesh, scale, a, b))
        .filter_map(|(&(a, b), &t)| pick(a, b, length(mesh, a, b)).map(|key| (key, (a, b), t)))
        .collect();
    long.sort_unstable_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
    let mut touched = vec![false; mesh.faces.len()];
    let mut splits = 0;
    for (_, (a, b), [t1, t2]) in long {
        if splits == limit {
            break;
        }
        let interior = t1 != u32::MAX && t2 != u32::MAX;
        if [t1, t2].iter().any(|&t| t != u32::MAX && touched[t as usize]) {
            continue;
        }
        if [t1, t2].iter().any(|&t| t != u32::MAX && !mesh.faces[t as usize].iter().all(|&v| mesh.planar(v))) {
            continue;
        }
        // t1 runs a -> b: (a, b, c); t2 runs b -> a: (b, a, d).
        let c = (t1 != u32::MAX).then(|| third(mesh.faces[t1 as usize], a, b)).flatten();
        let d = (t2 != u32::MAX).then(|| third(mesh.faces[t2 as usize], b, a)).flatten();
        let (q, x, hint, role, s) = if interior {
            let (pa, pb) = (mesh.plane[a as usize], mesh.plane[b as usize]);
            let q = [0.5 * (pa[0] + pb[0]), 0.5 * (pa[1] + pb[1])];
            let Some((x, h)) = lift.lift(q, mesh.hint[a as usize]) else { continue };
            (q, x, h, Role::Free, 0.0)
        } else {
            // A boundary edge of an open surface: the new vertex on the track between them.
            let Some(track) = track else { continue };
            if mesh.role[a as usize] == Role::Free || mesh.role[b as usize] == Role::Free {
                continue;
            }
            let s = arc_midpoint(track, arc[a as usize], arc[b as usize]);
            let (q, x) = track.at(s);
            (q, x, u32::MAX, Role::Boundary, s)
        };
        // The new faces, checked before anything changes.
        let mut new_faces: Vec<(usize, [u32; 3], [u32; 3])> = Vec::new();
        let w = mesh.plane.len() as u32;
        if let Some(c) = c {
            new_faces.push((t1 as usize, [a, w, c], [w, b, c]));
        }
        if let Some(d) = d {
            new_faces.push((t2 as usize, [b, w, d], [w, a, d]));
        }
        // A split cannot fold the planar mesh (the new point is on the edge, or on the
        // boundary track beyond it). Where the map is not resolved at the edge's scale (the
        // lift of the planar midpoint far from the chord's midpoint, or a new face turned
        // away from the face it splits) the edge crosses a fold of the surface that the
        // remesh cannot follow: it is left alone.
        let (xa, xb) = (mesh.position[a as usize], mesh.position[b as usize]);
        let chord_mid = [0.5 * (xa[0] + xb[0]), 0.5 * (xa[1] + xb[1]), 0.5 * (xa[2] + xb[2])];
        if norm(sub(x, chord_mid)) > MAX_LIFT_OFFSET * norm(sub(xa, xb)) {
            continue;
        }
        let ok = new_faces.iter().all(|&(t, f, g)| {
            let old = mesh.faces[t].map(|v| mesh.position[v as usize]);
            let n0 = cross(sub(old[1], old[0]), sub(old[2], old[0]));
            [f, g].iter().all(|h| {
                let p = h.map(|v| if v == w { q } else { mesh.plane[v as usize] });
                let y = h.map(|v| if v == w { x } else { mesh.position[v as usize] });
                let n1 = cross(sub(y[1], y[0]), sub(y[2], y[0]));
                mesh.oriented(p[0], p[1], p[2], 0.0) && norm(n1) > 0.0 && dot(n0, n1) > MAX_TURN_COS * norm(n0) * norm(n1)
            })
        });
        if new_faces.is_empty() || !ok {
            continue;
        }
        push_vertex(mesh, arc, q, x, hint, role, s);
        for (t, f, g) in new_faces {
            mesh.faces[t] = f;
            touched[t] = true;
            mesh.faces.push(g);
            touched.push(true);
        }
        splits += 1;
    }
    splits
}

/// Collapse the edges shorter than `min_len`, shortest first: a free vertex into its
/// neighbour (both free: at the planar midpoint), when the edge's ring is manifold after it
/// (exactly two common neighbours), no neighbour falls to valence 3, every moved face keeps
/// its orientation and side, and no edge becomes longer than `max_len`. Removed vertices
/// keep their slots with no face (see [`compact`]). Returns the number of collapses.
pub(crate) fn collapse_short_edges(mesh: &mut Shaping, incidence: &Incidence, lift: &SurfaceLift, min_len: f64, max_len: f64, local: &dyn Fn(u32, u32) -> f64) -> usize {
    collapse_edges(mesh, incidence, lift, &|a, b, l| (l < min_len * local(a, b)).then_some(l), usize::MAX, max_len, local)
}

/// Collapse at most `limit` of the interior edges `(a, b)` (length `l`) for which `pick(a, b,
/// l)` gives a key, smallest key first, with the checks of [`collapse_short_edges`] (`max_len`
/// and `local` bound the edges a collapse may create). Returns the number of collapses.
pub(crate) fn collapse_edges(mesh: &mut Shaping, incidence: &Incidence, lift: &SurfaceLift, pick: &dyn Fn(u32, u32, f64) -> Option<f64>, limit: usize, max_len: f64, local: &dyn Fn(u32, u32) -> f64) -> usize {
    let edges = edge_faces(&mesh.faces);
    let scale = mean_scale(mesh);
    let mut short: Vec<(f64, (u32, u32), [u32; 2])> = edges
        .iter()
        .filter(|(&(a, b), t)| t[0] != u32::MAX && t[1] != u32::MAX && mesh.planar(a) && mesh.planar(b) && resolved(mesh, scale, a, b))
        .filter_map(|(&(a, b), &t)| pick(a, b, length(mesh, a, b)).map(|key| (key, (a, b), t)))
        .collect();
    short.sort_unstable_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
    let n = mesh.plane.len();
    let mut touched = vec![false; n];
    let mut removed_face = vec![false; mesh.faces.len()];
    let mut collapses = 0;
    for (_, (a, b), [t1, t2]) in short {
        if collapses == limit {
            break;
        }
        if touched[a as usize] || touched[b as usize] || !mesh.planar(a) || !mesh.planar(b) {
            continue;
        }
        // Remove u, keep v.
        let (u, v) = match (mesh.role[a as usize], mesh.role[b as usize]) {
            (Role::Free, Role::Free) => (a, b),
            (Role::Free, _) => (a, b),
            (_, Role::Free) => (b, a),
            _ => continue,
        };
        let (nu, nv) = (neighbours(mesh, incidence, u), neighbours(mesh, incidence, v));
        let common = nu.iter().filter(|x| nv.binary_search(x).is_ok()).count();
        if common != 2 {
            continue;
        }
        let c = third(mesh.faces[t1 as usize], a, b);
        let d = third(mesh.faces[t2 as usize], b, a);
        let (Some(c), Some(d)) = (c, d) else { continue };
        if [c, d].iter().any(|&x| incidence.of(x as usize).len() <= 3) {
            continue;
        }
        // The merged vertex's valence: the union of both rings less u and v themselves.
        let merged = nu.len() + nv.len() - common - 2;
        if merged > MAX_VALENCE - usize::from(mesh.role[v as usize] != Role::Free) * 2 {
            continue;
        }
        let both_free = mesh.role[v as usize] == Role::Free;
        let q = if both_free {
            let (pu, pv) = (mesh.plane[u as usize], mesh.plane[v as usize]);
            [0.5 * (pu[0] + pv[0]), 0.5 * (pu[1] + pv[1])]
        } else {
            mesh.plane[v as usize]
        };
        // Every face around u or v that survives, with both at the merged point: in the
        // chart first, before the lift (most candidates that fail, fail there).
        let ring: Vec<u32> = incidence.of(u as usize).iter().chain(incidence.of(v as usize)).copied().filter(|&t| t != t1 && t != t2).collect();
        if !merge_keeps_orientation(mesh, &ring, (u, v), q) {
            continue;
        }
        let (x, hint) = if both_free {
            let Some(lifted) = lift.lift(q, mesh.hint[v as usize]) else { continue };
            lifted
        } else {
            (mesh.position[v as usize], mesh.hint[v as usize])
        };
        if !merge_keeps_faces(mesh, &ring, &[t1, t2], (u, v), (q, x), max_len * local(u, v), Judge::EachFace) {
            continue;
        }
        for &t in &ring {
            for w in mesh.faces[t as usize].iter_mut() {
                if *w == u {
                    *w = v;
                }
            }
        }
        removed_face[t1 as usize] = true;
        removed_face[t2 as usize] = true;
        mesh.plane[v as usize] = q;
        mesh.position[v as usize] = x;
        mesh.hint[v as usize] = hint;
        for w in nu.iter().chain(&nv).chain([&u, &v]) {
            touched[*w as usize] = true;
        }
        collapses += 1;
    }
    if collapses > 0 {
        drop_faces(&mut mesh.faces, &removed_face);
    }
    collapses
}

/// How [`merge_keeps_faces`] judges a merge's long edges and small angles.
#[derive(Clone, Copy, PartialEq)]
enum Judge {
    /// Face by face: no edge from the merged point longer than `max_len`, no smallest angle
    /// below the face's own before or [`COLLAPSE_MIN_ANGLE_DEG`].
    EachFace,
    /// The ring as a whole (a boundary collapse among needles, whose faces each change a
    /// little either way): no edge longer than `max_len` that was not already, no smallest
    /// angle below the ring's before (the removed faces included) or
    /// [`COLLAPSE_MIN_ANGLE_DEG`].
    Ring,
}

/// Whether the faces `ring` around `u` and `v` all have planar points and keep their planar
/// orientation with both at the planar point `q` (the first test of [`merge_keeps_faces`]).
fn merge_keeps_orientation(mesh: &Shaping, ring: &[u32], uv: (u32, u32), q: [f64; 2]) -> bool {
    ring.iter().all(|&t| face_keeps_orientation(mesh, t, uv, q))
}

/// Whether face `t` has planar points and keeps its planar orientation with `u` and `v` at
/// the planar point `q`.
fn face_keeps_orientation(mesh: &Shaping, t: u32, (u, v): (u32, u32), q: [f64; 2]) -> bool {
    let f = mesh.faces[t as usize];
    f.iter().all(|&w| mesh.planar(w)) && {
        let p = f.map(|w| if w == u || w == v { q } else { mesh.plane[w as usize] });
        mesh.oriented(p[0], p[1], p[2], 0.0)
    }
}

/// Whether the faces `ring` around `u` and `v`, with both at the planar point `q` and its
/// lift `x`, all keep their planar orientation and their side on the surface (a normal turned
/// by less than 45 degrees), with long edges and small angles as `judge` says; `removed`:
/// the faces the merge removes.
fn merge_keeps_faces(mesh: &Shaping, ring: &[u32], removed: &[u32], (u, v): (u32, u32), (q, x): ([f64; 2], [f64; 3]), max_len: f64, judge: Judge) -> bool {
    let angle_before = |t: u32| {
        let old = mesh.faces[t as usize].map(|w| mesh.position[w as usize]);
        smallest_angle(old[0], old[1], old[2])
    };
    // The ring's smallest angle before, for Judge::Ring only (atan2 is most of this check's
    // time).
    let ring_before = std::cell::OnceCell::new();
    let ring_before = || *ring_before.get_or_init(|| ring.iter().chain(removed).map(|&t| angle_before(t)).fold(f64::INFINITY, f64::min));
    ring.iter().all(|&t| {
        if !face_keeps_orientation(mesh, t, (u, v), q) {
            return false;
        }
        let f = mesh.faces[t as usize];
        let y = f.map(|w| if w == u || w == v { x } else { mesh.position[w as usize] });
        let old = f.map(|w| mesh.position[w as usize]);
        let n0 = cross(sub(old[1], old[0]), sub(old[2], old[0]));
        let n1 = cross(sub(y[1], y[0]), sub(y[2], y[0]));
        let keeps_side = dot(n0, n1) > MAX_TURN_COS * norm(n0) * norm(n1);
        if !keeps_side {
            return false;
        }
        // The face's corner among u and v, whose edges the merge moves.
        let end = if f.contains(&u) { u } else { v };
        let long = f.iter().any(|&w| {
            let was_long = norm(sub(mesh.position[w as usize], mesh.position[end as usize])) > max_len;
            w != u && w != v && norm(sub(mesh.position[w as usize], x)) > max_len && !(judge == Judge::Ring && was_long)
        });
        if long {
            return false;
        }
        let before = if judge == Judge::Ring { ring_before() } else { angle_before(t) };
        let sliver = smallest_angle(y[0], y[1], y[2]) < before.min(COLLAPSE_MIN_ANGLE_DEG.to_radians());
        !sliver
    })
}

/// Collapse the boundary edges of an open remesh shorter than `min_len` times `local(a, b)`,
/// shortest first: a sliding vertex into its neighbour on the boundary, both then at their
/// arc midpoint on the input's boundary `track` (else where either end is; a corner stays
/// where it is), with the checks of [`collapse_short_edges`] judged over the ring
/// ([`Judge::Ring`]). Unlike an interior edge's, a boundary edge is collapsed however the map
/// stretches it: its new vertex is on the input's boundary exactly, no lift is involved. The
/// cap grid's rim holds as many vertices as its length on the cap asks for, and where the map
/// stretches a short boundary (a closed surface with a hole) that is several times what its
/// length on the surface asks for (docs/method.md section 18, "Short boundaries"). The loop
/// keeps at least four vertices. Returns the number of collapses.
pub(crate) fn collapse_short_boundary_edges(mesh: &mut Shaping, incidence: &Incidence, track: &Track, arc: &mut [f64], min_len: f64, max_len: f64, local: &dyn Fn(u32, u32) -> f64) -> usize {
    let edges = edge_faces(&mesh.faces);
    let mut short: Vec<(f64, (u32, u32), u32)> = edges
        .iter()
        .filter_map(|(&(a, b), t)| {
            let face = match *t {
                [t1, u32::MAX] => t1,
                [u32::MAX, t2] => t2,
                _ => return None,
            };
            let l = length(mesh, a, b);
            (mesh.planar(a) && mesh.planar(b) && l < min_len * local(a, b)).then_some((l, (a, b), face))
        })
        .collect();
    let mut loop_vertices = edges.values().filter(|t| t.contains(&u32::MAX)).count();
    short.sort_unstable_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
    let mut touched = vec![false; mesh.plane.len()];
    let mut removed_face = vec![false; mesh.faces.len()];
    let mut collapses = 0;
    for (_, (a, b), t1) in short {
        if loop_vertices <= 4 {
            break;
        }
        if touched[a as usize] || touched[b as usize] {
            continue;
        }
        // Remove u, keep v: a corner (fixed) is kept.
        let (u, v) = match (mesh.role[a as usize], mesh.role[b as usize]) {
            (Role::Boundary, Role::Boundary | Role::Fixed) => (a, b),
            (Role::Fixed, Role::Boundary) => (b, a),
            _ => continue,
        };
        let (nu, nv) = (neighbours(mesh, incidence, u), neighbours(mesh, incidence, v));
        if nu.iter().filter(|x| nv.binary_search(x).is_ok()).count() != 1 {
            continue;
        }
        let f = mesh.faces[t1 as usize];
        let Some(c) = third(f, a, b).or_else(|| third(f, b, a)) else { continue };
        if incidence.of(c as usize).len() <= 3 || nu.len() + nv.len() - 3 > MAX_VALENCE - 2 {
            continue;
        }
        // The merged point: the arc midpoint, else where either end is (the rim's faces are
        // thin in the plane, and a tangential move turns some over); a corner's own point.
        let at = |w: u32| (mesh.plane[w as usize], mesh.position[w as usize], arc[w as usize]);
        let candidates = if mesh.role[v as usize] == Role::Boundary {
            let s = arc_midpoint(track, arc[u as usize], arc[v as usize]);
            let (q, x) = track.at(s);
            vec![(q, x, s), at(v), at(u)]
        } else {
            vec![at(v)]
        };
        let ring: Vec<u32> = incidence.of(u as usize).iter().chain(incidence.of(v as usize)).copied().filter(|&t| t != t1).collect();
        let Some((q, x, s)) = candidates.into_iter().find(|&(q, x, _)| merge_keeps_faces(mesh, &ring, &[t1], (u, v), (q, x), max_len * local(u, v), Judge::Ring)) else {
            continue;
        };
        for &t in &ring {
            for w in mesh.faces[t as usize].iter_mut() {
                if *w == u {
                    *w = v;
                }
            }
        }
        removed_face[t1 as usize] = true;
        mesh.plane[v as usize] = q;
        mesh.position[v as usize] = x;
        mesh.hint[v as usize] = u32::MAX;
        arc[v as usize] = s;
        for w in nu.iter().chain(&nv).chain([&u, &v]) {
            touched[*w as usize] = true;
        }
        loop_vertices -= 1;
        collapses += 1;
    }
    if collapses > 0 {
        drop_faces(&mut mesh.faces, &removed_face);
    }
    collapses
}

/// Drop the vertices that no face uses, renumbering the rest in order; `arc` follows.
pub(crate) fn compact(mesh: &mut Shaping, arc: &mut Vec<f64>) {
    let n = mesh.plane.len();
    let mut used = vec![false; n];
    for f in &mesh.faces {
        for &v in f {
            used[v as usize] = true;
        }
    }
    if used.iter().all(|&u| u) {
        return;
    }
    let mut index = vec![u32::MAX; n];
    let mut next = 0u32;
    for v in 0..n {
        if used[v] {
            index[v] = next;
            next += 1;
        }
    }
    for f in mesh.faces.iter_mut() {
        *f = f.map(|v| index[v as usize]);
    }
    let keep = |v: usize| used[v];
    fn filter<T: Copy>(xs: &mut Vec<T>, keep: &dyn Fn(usize) -> bool) {
        let mut i = 0;
        xs.retain(|_| {
            i += 1;
            keep(i - 1)
        });
    }
    filter(&mut mesh.plane, &keep);
    filter(&mut mesh.position, &keep);
    filter(&mut mesh.hint, &keep);
    filter(&mut mesh.role, &keep);
    filter(&mut mesh.has_plane, &keep);
    filter(arc, &keep);
}
