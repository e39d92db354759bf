//! The remesh's shape stage (`--optimize shape+area`, the default) against the area-only
//! remesh (`--optimize area`) on shared meshes, open and closed: isotropic triangles (few
//! angles below 30 degrees, a high mean smallest angle), areas still near-equal, every vertex
//! on the input surface, an open surface's boundary on the input's boundary, the input's
//! topology kept, and a square sheet's corners kept.

use capmesh::io::read_mesh;
use capmesh::mesh::{validate, SurfaceKind, TriMesh};
use capmesh::progress::NoProgress;
use capmesh::metrics::angles::{angle_quality, face_angle_range};
use capmesh::remesh::{remesh, CapGrid, Optimize, Placement, RemeshOptions};

mod common;

fn load(name: &str) -> TriMesh {
    read_mesh(&common::data(name)).unwrap()
}

fn run(mesh: &TriMesh, optimize: Optimize) -> (TriMesh, capmesh::remesh::RemeshReport) {
    let options = RemeshOptions::default().with_placement(Placement::OnSurface).with_grid(CapGrid::Uniform { faces: 5000 }).with_optimize(optimize);
    remesh(mesh, &options, &NoProgress).unwrap()
}

/// The faces of `mesh` with an angle below `deg` degrees (the metrics' per-face angles).
fn faces_below(mesh: &TriMesh, deg: f64) -> usize {
    (0..mesh.n_faces())
        .filter(|&f| {
            let [a, b, c] = mesh.face_points(f);
            face_angle_range(a, b, c).0 < deg
        })
        .count()
}

/// The faces using each edge `(a, b)`, `a < b`, of `mesh`.
fn edge_uses(mesh: &TriMesh) -> std::collections::HashMap<(u32, u32), usize> {
    let mut count = std::collections::HashMap::new();
    for f in &mesh.faces {
        for k in 0..3 {
            let (a, b) = (f[k], f[(k + 1) % 3]);
            *count.entry((a.min(b), a.max(b))).or_insert(0) += 1;
        }
    }
    count
}

/// Boundary vertices of a mesh (on an edge with one face).
fn boundary_vertices(mesh: &TriMesh) -> Vec<usize> {
    let count = edge_uses(mesh);
    let mut out: Vec<usize> = count.iter().filter(|(_, &c)| c == 1).flat_map(|(&(a, b), _)| [a as usize, b as usize]).collect();
    out.sort_unstable();
    out.dedup();
    out
}

/// The boundary edges of `mesh`, as pairs of end points.
fn boundary_segments(mesh: &TriMesh) -> Vec<([f64; 3], [f64; 3])> {
    edge_uses(mesh).iter().filter(|(_, &c)| c == 1).map(|(&(a, b), _)| (mesh.vertices[a as usize], mesh.vertices[b as usize])).collect()
}

/// Distance from `p` to the segments `rim` ([`boundary_segments`]).
fn distance_to_boundary(rim: &[([f64; 3], [f64; 3])], p: [f64; 3]) -> f64 {
    rim.iter()
        .map(|&(a, b)| {
            let e: [f64; 3] = std::array::from_fn(|k| b[k] - a[k]);
            let w: [f64; 3] = std::array::from_fn(|k| p[k] - a[k]);
            let len2: f64 = e.iter().map(|x| x * x).sum();
            let t = if len2 > 0.0 { (w.iter().zip(&e).map(|(x, y)| x * y).sum::<f64>() / len2).clamp(0.0, 1.0) } else { 0.0 };
            (0..3).map(|k| (a[k] + t * e[k] - p[k]).powi(2)).sum::<f64>().sqrt()
        })
        .fold(f64::INFINITY, f64::min)
}


/// The shape stage against the area-only remesh of the same map.
fn check(name: &str) -> capmesh::remesh::RemeshReport {
    check_with(name, 0.04)
}

/// [`check`] with a bound on `d_face_rel` (the issue's: 0.035, and 0.08 on the bird skull and
/// the hand, whose map is the most anisotropic; these bounds leave a margin).
fn check_with(name: &str, max_d_face: f64) -> capmesh::remesh::RemeshReport {
    check_mesh(name, &load(name), max_d_face).1
}

/// [`check_with`] on `mesh` (called `name` in messages); the remesh too.
fn check_mesh(name: &str, mesh: &TriMesh, max_d_face: f64) -> (TriMesh, capmesh::remesh::RemeshReport) {
    let (shaped, rep) = run(mesh, Optimize::ShapeAndArea);
    let (plain, plain_rep) = run(mesh, Optimize::Area);
    let (a, b) = (angle_quality(&shaped), angle_quality(&plain));
    eprintln!(
        "{name}: mean smallest angle {:.1} (area only {:.1}), below 30 deg {:.2}% ({:.2}%), smallest {:.1} ({:.1}), d_face_rel {:.4} ({:.4}), flips {}",
        a.mean_min_angle_deg,
        b.mean_min_angle_deg,
        100.0 * a.share_below_30,
        100.0 * b.share_below_30,
        a.min_angle_deg,
        b.min_angle_deg,
        rep.quality.d_face_relative,
        plain_rep.quality.d_face_relative,
        rep.shape.flips
    );
    // The report's figures are the mesh's.
    let stage = &rep.shape;
    assert!(stage.iterations > 0 && stage.after.share_below_30 <= stage.before.share_below_30.max(0.005), "{name}: {stage:?}");
    assert_eq!(validate(&shaped).unwrap().0, validate(mesh).unwrap().0, "{name}: topology changed");
    assert!(a.share_below_30 <= 0.04, "{name}: {:.3} of the faces have an angle below 30 degrees", a.share_below_30);
    // The bound is 48 degrees on every shared mesh (48.1 at worst at the last
    // measurement); the margin is for rounding differences between builds.
    assert!(a.mean_min_angle_deg >= 47.5, "{name}: mean smallest angle {:.1}", a.mean_min_angle_deg);
    // The bound: the vertices of faces left thin after the last flips are moved for
    // shape (`shape::worst`; 16.3 degrees at worst on the shared meshes at the last
    // measurement).
    assert!(a.min_angle_deg >= 15.0, "{name}: smallest angle {:.1}", a.min_angle_deg);
    // Where the pulled-back grid is already well shaped (the MEG helmet, nearly a cap) the
    // stage keeps it so; elsewhere it gains at least 5 degrees.
    let gain = if b.share_below_30 > 0.05 { 5.0 } else { 0.0 };
    assert!(a.mean_min_angle_deg >= b.mean_min_angle_deg + gain, "{name}: the shape stage gained too little");
    assert!(a.share_below_30 <= (0.2 * b.share_below_30).max(0.005), "{name}: slivers {:.3} vs {:.3}", a.share_below_30, b.share_below_30);
    assert!(rep.quality.d_face_relative <= max_d_face, "{name}: d_face_rel {}", rep.quality.d_face_relative);
    assert!((rep.quality.faces as f64 - 5000.0).abs() <= 500.0, "{name}: {} faces", rep.quality.faces);
    assert_eq!(rep.quality.zero_area_faces, 0, "{name}");
    // No face crosses another unless the input's own faces do, and the report says so.
    let q = &rep.quality;
    assert!(q.self_intersecting_faces <= q.self_intersecting_faces_input, "{name}: {} self-crossing faces (input {})", q.self_intersecting_faces, q.self_intersecting_faces_input);
    if q.self_intersecting_faces_input == 0 {
        assert_eq!(q.self_intersecting_faces, 0, "{name}");
    }
    assert_eq!(rep.shape.uncross.after, q.self_intersecting_faces, "{name}: {:?}", rep.shape.uncross);
    // The slivers the report counts are the remesh's (faces with a planar point at every
    // corner: all of them on an open surface).
    let below_15 = faces_below(&shaped, 15.0);
    assert!(rep.shape.uncross.slivers_after <= below_15, "{name}: {:?}, {below_15} faces below 15 degrees", rep.shape.uncross);
    if validate(mesh).unwrap().0 == SurfaceKind::OpenDisk {
        assert_eq!(rep.shape.uncross.slivers_after, below_15, "{name}");
    }
    // Crossings counted as the input's only where the input crosses itself.
    assert!(rep.shape.uncross.at_input_crossings <= rep.shape.uncross.after, "{name}: {:?}", rep.shape.uncross);
    if q.self_intersecting_faces_input == 0 {
        assert_eq!(rep.shape.uncross.at_input_crossings, 0, "{name}");
    }
    assert!((1..=3).contains(&rep.shape.starts), "{name}: {} starts", rep.shape.starts);
    assert!(rep.quality.d_surface_vertex_relative < 1e-9, "{name}: vertices off the surface");
    if validate(mesh).unwrap().0 == SurfaceKind::OpenDisk {
        let diag = mesh.bounding_box_diagonal();
        let rim = boundary_segments(mesh);
        let worst = boundary_vertices(&shaped).iter().map(|&v| distance_to_boundary(&rim, shaped.vertices[v])).fold(0.0, f64::max);
        assert!(worst < 1e-9 * diag, "{name}: a boundary vertex is {worst} off the input's boundary");
    }
    (shaped, rep)
}

/// Mean length of the boundary edges and of the interior edges of `mesh`.
fn boundary_and_interior_edges(mesh: &TriMesh) -> (f64, f64) {
    let mut sums = [(0.0, 0usize); 2];
    for (&(a, b), &c) in &edge_uses(mesh) {
        let (p, q) = (mesh.vertices[a as usize], mesh.vertices[b as usize]);
        let s = &mut sums[usize::from(c == 2)];
        s.0 += (0..3).map(|k| (p[k] - q[k]).powi(2)).sum::<f64>().sqrt();
        s.1 += 1;
    }
    (sums[0].0 / sums[0].1 as f64, sums[1].0 / sums[1].1 as f64)
}

/// The lung lobe without the faces within 4 edges of its lowest vertex: an open surface whose
/// disk map stretches its short boundary, so that the cap grid's rim puts about four times the
/// vertices its length on the surface asks for on it (boundary edges 0.23 of the interior
/// ones, smallest angle 11.7 degrees, d_face_rel 0.037). Boundary edges below half the target
/// length are collapsed along the input's boundary (`resample::collapse_short_boundary_edges`):
/// 0.70, 30.5 degrees, 0.017.
#[test]
fn a_short_boundary_gets_the_vertices_its_length_asks_for() {
    let mesh = common::holed("closed_lung_rml_chaste.obj.gz", 4);
    let (shaped, rep) = check_mesh("lung lobe with a hole", &mesh, 0.035);
    let (boundary, interior) = boundary_and_interior_edges(&shaped);
    eprintln!("lung lobe with a hole: boundary edges {:.3} of the interior ones, smallest angle {:.1}", boundary / interior, rep.quality.min_angle_deg);
    assert!(boundary >= 0.5 * interior, "boundary edges {boundary} against {interior} inside");
    assert!(rep.quality.min_angle_deg >= 20.0, "smallest angle {:.1}", rep.quality.min_angle_deg);
}

/// The face scan crosses itself (402 faces by MeshLab's test): its remesh's crossing faces are
/// all at the input's crossings, so they do not send the shape stage to another start.
#[test]
fn face() {
    let rep = check("open_face_choi.obj.gz");
    let u = &rep.shape.uncross;
    assert!(u.after > 0 && u.at_input_crossings == u.after, "{u:?}");
    assert_eq!(rep.shape.starts, 1);
}

#[test]
fn left_ventricle() {
    check("open_lv_endo_rabbit_chaste.obj.gz");
}

/// Nearly a cap already: its pulled-back grid is near-isotropic and is kept as the start.
#[test]
fn meg_helmet() {
    assert_eq!(check("open_meg_helmet_babysquid_mne.obj.gz").shape.start, capmesh::remesh::shape::Start::Grid);
}

/// The grid's lift is stretched: the shape stage starts from the isotropic sample. Its
/// punctured quad is 3.5 remesh faces: merged into one vertex (`MERGE_QUAD_FACES`), not left
/// as about 19 faces a sixth of the mean area (d_face_rel 0.0323 then, 0.0288 merged, 0.0314
/// since the relaxation's angle flips keep the valence flips: within issue 26's 0.035).
#[test]
fn closed_bunny() {
    let rep = check("closed_bunny_npm.obj.gz");
    assert_eq!(rep.shape.start, capmesh::remesh::shape::Start::Sample);
    assert!(rep.quality.d_face_relative <= 0.035, "d_face_rel {:.4}", rep.quality.d_face_relative);
}

/// The lung lobe's thinnest face (22.5 degrees, three free corners of valence 5-8 that the
/// polish's step could not widen) is raised by the compass search of `shape::worst` (26.4).
#[test]
fn closed_lung_lobe() {
    let rep = check("closed_lung_rml_chaste.obj.gz");
    assert!(rep.quality.min_angle_deg >= 25.0, "smallest angle {:.1}", rep.quality.min_angle_deg);
}

/// The 12k brain at 20000 faces: its punctured quad is 2.4 remesh faces, merged into one
/// vertex since the limit is four faces (left as a ring and a disk: smallest angle 10.1
/// degrees, d_face_rel 0.0211; merged 25.2 and 0.0172).
#[test]
fn closed_brain12k_at_20000_faces_merges_its_bottom() {
    merged_bottom_at("closed_brain12k_choi.obj.gz", 20000, 20.0, 0.019);
}

/// The remesh of `name` at `faces` faces (a closed surface whose bottom is merged): its
/// smallest angle at least `min_angle` degrees and d_face_rel at most `max_d_face`.
fn merged_bottom_at(name: &str, faces: usize, min_angle: f64, max_d_face: f64) {
    let mesh = load(name);
    let options = RemeshOptions::default().with_grid(CapGrid::Uniform { faces });
    let (out, rep) = remesh(&mesh, &options, &NoProgress).unwrap();
    let a = angle_quality(&out);
    eprintln!("{name} at {faces}: smallest angle {:.1}, mean {:.2}, d_face_rel {:.4}", a.min_angle_deg, a.mean_min_angle_deg, rep.quality.d_face_relative);
    assert!(a.min_angle_deg >= min_angle, "smallest angle {:.1}", a.min_angle_deg);
    assert!(rep.quality.d_face_relative <= max_d_face, "d_face_rel {:.4}", rep.quality.d_face_relative);
    assert_eq!(validate(&out).unwrap().0, SurfaceKind::ClosedSphere);
}

/// Thin bony ridges: the equalized remesh crosses itself there before the last pass.
#[test]
fn closed_bird_skull() {
    check_with("closed_bird_skull_CPallidusA_choi.obj.gz", 0.09);
}

/// A decimated copy of the lung lobe (graded triangles): its bottom fan's crowded ring left a
/// vertex of valence 4 pressed against a spoke (a 7.4-degree face) until the removal of
/// low-valence vertices at slivers (`remesh::shape::sliver`, unit-tested there); since the
/// relaxation's angle flips keep the valence flips, no such vertex is left (25.1 degrees).
#[test]
fn closed_lung_lobe_decimated() {
    let rep = check("closed_lung_rml_chaste_decimated.obj.gz");
    assert!(rep.quality.min_angle_deg >= 15.0, "smallest angle {:.1}", rep.quality.min_angle_deg);
}

/// The bunny subdivided twice (58784 faces, the same surface), mapped at one level
/// (`with_coarse_map(false)`): the end the radius search keeps (its search map within 2% of
/// the other's) maps poorly around the puncture and its remesh misses the bar, so the other
/// end is mapped and remeshed too and the better kept. By default the 29k vertices are mapped
/// through a copy of 6000 ([`RemeshOptions::coarse_map`]), whose first end meets the bars.
#[test]
fn closed_bunny_subdivided_twice_tries_the_other_end() {
    let mesh = capmesh::mesh::subdivide_midpoint(&load("closed_bunny_npm.obj.gz"), 2);
    let options = RemeshOptions::default().with_placement(Placement::OnSurface).with_grid(CapGrid::Uniform { faces: 5000 });
    let (out, rep) = remesh(&mesh, &options.clone().with_coarse_map(false), &NoProgress).unwrap();
    let (copy_out, copy) = remesh(&mesh, &options, &NoProgress).unwrap();
    let c = angle_quality(&copy_out);
    eprintln!("through the copy: ends {}, mean smallest angle {:.2}, smallest {:.1}, d_face_rel {:.4}", copy.shape.ends, c.mean_min_angle_deg, c.min_angle_deg, copy.quality.d_face_relative);
    assert_eq!(copy.param.multilevel.as_ref().map(|m| m.coarse_vertices), Some(capmesh::remesh::remesh_copy_vertices(5000)));
    assert!(c.mean_min_angle_deg >= 48.0 && c.min_angle_deg >= 15.0 && copy.quality.d_face_relative <= 0.035 && copy.quality.self_intersecting_faces == 0);
    let a = angle_quality(&out);
    eprintln!("subdivided bunny: ends {}, mean smallest angle {:.2}, smallest {:.1}, d_face_rel {:.4}", rep.shape.ends, a.mean_min_angle_deg, a.min_angle_deg, rep.quality.d_face_relative);
    assert_eq!(rep.shape.ends, 2);
    let finished: Vec<f64> = rep.param.puncture_trials.iter().filter_map(|t| t.mean_abs_area_distortion).collect();
    assert_eq!(finished.len(), 2, "{:?}", rep.param.puncture_trials);
    // The bars at 5000 faces (the first end's remesh: d_face_rel 0.049, smallest angle
    // 6.0, mean smallest angle 47.3-48.0).
    assert!(a.mean_min_angle_deg >= 48.0, "mean smallest angle {:.2}", a.mean_min_angle_deg);
    assert!(a.min_angle_deg >= 15.0, "smallest angle {:.1}", a.min_angle_deg);
    assert!(rep.quality.d_face_relative <= 0.035, "d_face_rel {:.4}", rep.quality.d_face_relative);
    assert_eq!(rep.quality.self_intersecting_faces, 0);
    assert_eq!(validate(&out).unwrap().0, SurfaceKind::ClosedSphere);
}

/// The same copy at 10000 faces: the first end's remesh met the angle bar but spread its
/// areas (d_face_rel 0.049, above `RETRY_AREA_SPREAD` 0.04), so the other end was tried too;
/// since the area rebalancing (`remesh::shape::rebalance`) the first end's remesh is even
/// (0.026) and kept (the retry decision is unit-tested in `remesh::from_cap`).
#[test]
fn closed_bunny_subdivided_twice_at_10000_faces_has_even_areas() {
    let mesh = capmesh::mesh::subdivide_midpoint(&load("closed_bunny_npm.obj.gz"), 2);
    let options = RemeshOptions::default().with_grid(CapGrid::Uniform { faces: 10000 });
    let (out, rep) = remesh(&mesh, &options, &NoProgress).unwrap();
    let a = angle_quality(&out);
    eprintln!("subdivided bunny at 10000: ends {}, mean smallest angle {:.2}, d_face_rel {:.4}", rep.shape.ends, a.mean_min_angle_deg, rep.quality.d_face_relative);
    assert!(rep.quality.d_face_relative <= 0.035, "d_face_rel {:.4}", rep.quality.d_face_relative);
    assert!(a.mean_min_angle_deg >= 48.0, "mean smallest angle {:.2}", a.mean_min_angle_deg);
    assert_eq!(validate(&out).unwrap().0, SurfaceKind::ClosedSphere);
}

/// The closed hippocampus at 10000 faces: its punctured quad is between one and two remesh
/// faces, so the rim ring and bottom disk are merged into one vertex (`MERGE_QUAD_FACES`);
/// left as a ring bunched on the quad they gave a 15.0-degree sliver (19.8 merged).
#[test]
fn closed_hippocampus_at_10000_faces_merges_its_bottom() {
    merged_bottom_at("closed_hippocampus_choi.obj.gz", 10000, 17.0, 0.035);
}

#[test]
fn closed_hippocampus() {
    check("closed_hippocampus_choi.obj.gz");
}

/// A flat square sheet: the remesh keeps a vertex on each of its four corners, and its
/// boundary edges are about as long as its interior edges.
#[test]
fn square_sheet_keeps_its_corners() {
    let n = 40;
    let mut vertices = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            vertices.push([i as f64 / n as f64, j as f64 / n as f64, 0.0]);
        }
    }
    let mut faces = Vec::new();
    let id = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    for j in 0..n {
        for i in 0..n {
            faces.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            faces.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    let mesh = TriMesh::new(vertices, faces);
    let options = RemeshOptions::default().with_grid(CapGrid::Uniform { faces: 2000 });
    let (out, rep) = remesh(&mesh, &options, &NoProgress).unwrap();
    assert_eq!(rep.shape.corners_kept, 4, "{:?}", rep.shape);
    for corner in [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]] {
        let nearest = out.vertices.iter().map(|p| (p[0] - corner[0]).hypot(p[1] - corner[1])).fold(f64::INFINITY, f64::min);
        assert!(nearest < 1e-9, "corner {corner:?}: nearest remesh vertex {nearest} away");
    }
    let stats = angle_quality(&out);
    assert!(stats.share_below_30 < 0.02 && stats.mean_min_angle_deg > 45.0, "{stats:?}");
    // Boundary edges against interior edges.
    let b = boundary_vertices(&out);
    let on_boundary: std::collections::HashSet<usize> = b.into_iter().collect();
    let (mut sb, mut nb, mut si, mut ni) = (0.0, 0, 0.0, 0);
    for f in &out.faces {
        for k in 0..3 {
            let (u, v) = (f[k] as usize, f[(k + 1) % 3] as usize);
            let (p, q) = (out.vertices[u], out.vertices[v]);
            let len = (p[0] - q[0]).hypot(p[1] - q[1]);
            let both_on_boundary = on_boundary.contains(&u) && on_boundary.contains(&v) && (p[0] == q[0] || p[1] == q[1]) && [p[0], p[1], q[0], q[1]].iter().any(|&x| x == 0.0 || x == 1.0);
            if both_on_boundary {
                sb += len;
                nb += 1;
            } else {
                si += len;
                ni += 1;
            }
        }
    }
    let ratio = (sb / nb as f64) / (si / ni as f64);
    eprintln!("square sheet: {stats:?}, boundary edges {ratio:.3} times the interior ones");
    assert!((0.6..1.6).contains(&ratio), "boundary edges {ratio} times the interior ones");
}

/// With edge splits and collapses (the default; `--no-resample` turns them off) on a smooth open surface: the face count
/// stays near the target, every vertex stays on the surface and the boundary on the
/// input's boundary, the topology is kept, and the angles are at least as good as without.
#[test]
fn resampling_keeps_the_invariants() {
    let name = "open_lv_endo_rabbit_chaste.obj.gz";
    let mesh = load(name);
    let mut options = RemeshOptions::default().with_placement(Placement::OnSurface).with_grid(CapGrid::Uniform { faces: 5000 });
    assert!(options.shape.resample, "splits and collapses are the default");
    let (out, rep) = remesh(&mesh, &options, &NoProgress).unwrap();
    options.shape = options.shape.with_resample(false);
    let (plain, _) = remesh(&mesh, &options, &NoProgress).unwrap();
    let (a, b) = (angle_quality(&out), angle_quality(&plain));
    eprintln!("{name} resampled: {a:?}, {} splits, {} collapses; without: {b:?}", rep.shape.splits, rep.shape.collapses);
    assert!(rep.shape.splits > 0 && rep.shape.collapses > 0, "{:?}", rep.shape);
    assert_eq!(validate(&out).unwrap().0, SurfaceKind::OpenDisk);
    assert!((rep.quality.faces as f64 - 5000.0).abs() <= 500.0, "{} faces", rep.quality.faces);
    assert!(rep.quality.d_surface_vertex_relative < 1e-9);
    assert_eq!(rep.quality.zero_area_faces, 0);
    let diag = mesh.bounding_box_diagonal();
    let rim = boundary_segments(&mesh);
    let worst = boundary_vertices(&out).iter().map(|&v| distance_to_boundary(&rim, out.vertices[v])).fold(0.0, f64::max);
    assert!(worst < 1e-9 * diag, "a boundary vertex is {worst} off the input's boundary");
    assert!(a.mean_min_angle_deg >= b.mean_min_angle_deg && a.share_below_30 <= b.share_below_30.max(0.01), "{a:?} vs {b:?}");
}

/// The polish's global area steps (`ShapeOptions::area_steps`) make the bunny's areas more
/// equal than the same stage without them, at the same angles' bar; the report counts the
/// steps solved. (The gain depends on the map: since the smoothing's candidates are scored
/// after refinement sweeps, the hippocampal sheet's d_face_rel goes 0.0201 -> 0.0191 only,
/// the bunny's 0.0353 -> 0.0290.)
#[test]
fn global_area_steps_equalize_the_areas() {
    let mesh = load("closed_bunny_npm.obj.gz");
    let with_steps = |steps: usize| {
        let shape = capmesh::remesh::shape::ShapeOptions::default().with_area_steps(steps);
        let options = RemeshOptions::default().with_grid(CapGrid::Uniform { faces: 5000 }).with_shape(shape);
        remesh(&mesh, &options, &NoProgress).unwrap()
    };
    let (plain_mesh, plain) = with_steps(0);
    let (stepped_mesh, stepped) = with_steps(6);
    eprintln!("bunny d_face_rel without / with global steps: {:.4} / {:.4}", plain.quality.d_face_relative, stepped.quality.d_face_relative);
    assert_eq!((plain.shape.area_steps, stepped.shape.area_steps), (0, 6));
    assert!(stepped.quality.d_face_relative < 0.9 * plain.quality.d_face_relative, "{:.4} vs {:.4}", stepped.quality.d_face_relative, plain.quality.d_face_relative);
    for out in [&plain_mesh, &stepped_mesh] {
        let a = angle_quality(out);
        assert!(a.mean_min_angle_deg >= 48.0 && a.min_angle_deg >= 15.0, "{a:?}");
    }
}

/// The 12k brain's remesh kept a face of 15.9 degrees after the last flips and sliver
/// removals; its vertices' moves for shape (`shape::worst`) raise the smallest angle above 20
/// degrees, with the areas still within the bar.
#[test]
fn thin_faces_are_moved_for_shape() {
    let mesh = load("closed_brain12k_choi.obj.gz");
    let (out, rep) = run(&mesh, Optimize::ShapeAndArea);
    let a = angle_quality(&out);
    eprintln!("12k brain: smallest angle {:.2}, moves for shape {}, d_face_rel {:.4}", a.min_angle_deg, rep.shape.angle_moves, rep.quality.d_face_relative);
    assert!(rep.shape.angle_moves > 0, "{:?}", rep.shape);
    assert!(a.min_angle_deg >= 20.0, "{a:?}");
    assert!(rep.quality.d_face_relative <= 0.035, "{}", rep.quality.d_face_relative);
}

/// The remesh of `name` at 5000 faces without and with `Creases::Keep`.
fn without_and_with_creases(name: &str) -> ((TriMesh, capmesh::remesh::RemeshReport), (TriMesh, capmesh::remesh::RemeshReport)) {
    let mesh = load(name);
    let mut options = RemeshOptions::default().with_placement(Placement::OnSurface).with_grid(CapGrid::Uniform { faces: 5000 });
    let plain = remesh(&mesh, &options, &NoProgress).unwrap();
    options.shape = options.shape.with_creases(capmesh::Creases::Keep);
    (plain, remesh(&mesh, &options, &NoProgress).unwrap())
}

/// `Creases::Keep` on the lung lobe (a sharp edge, its faces' normals more than
/// 60 degrees apart):
/// vertices go onto the crease and are joined along it, so the sampled distance to the input
/// falls by more than a third while the angles and areas keep their bars.
#[test]
fn creases_are_kept_on_the_lung_lobe() {
    let ((_, plain), (kept, rep)) = without_and_with_creases("closed_lung_rml_chaste.obj.gz");
    let (p, k, s) = (&plain.quality, &rep.quality, &rep.shape);
    eprintln!("plain: d_surf {:.3e}; creases: {:.3e}, {} vertices, {}/{} joined, {} freed", p.d_surface_sampled_relative, k.d_surface_sampled_relative, s.crease_vertices, s.crease_edges, s.crease_pairs, s.crease_released);
    assert_eq!(plain.shape.crease_vertices, 0, "off by default");
    assert!(k.d_surface_sampled_relative < 0.65 * p.d_surface_sampled_relative);
    assert!(s.crease_vertices >= 50 && 4 * s.crease_edges >= 3 * s.crease_pairs, "{s:?}");
    assert!(k.d_face_relative <= 0.035 && k.d_surface_vertex_relative < 1e-9 && k.zero_area_faces == 0, "{k:?}");
    let a = angle_quality(&kept);
    assert!(a.mean_min_angle_deg >= 48.0 && a.share_below_30 <= 0.02 && a.min_angle_deg >= 15.0, "{a:?}");
}

/// The hippocampal sheet's sharp edges are the steps of a segmentation, sharp between two
/// input faces but not at the remesh's scale: `Creases::Keep` finds no crease there and the
/// remesh is the one without it.
#[test]
fn a_staircase_is_not_a_crease() {
    let ((plain, _), (kept, rep)) = without_and_with_creases("open_hippocampus_sheet_hippunfold.obj.gz");
    assert_eq!(rep.shape.crease_vertices, 0, "{:?}", rep.shape);
    assert_eq!(plain.faces, kept.faces);
    assert_eq!(plain.vertices, kept.vertices);
}

/// The hand's remesh had regions of faces too small beside regions too large, which the
/// polish's local steps could not even out (`d_face_rel` 0.0426 at 5000 faces): the area
/// rebalancing collapses edges in the first and splits as many in the second.
#[test]
fn open_hand_rebalances_its_areas() {
    let (out, rep) = run(&load("open_hand_choi.obj.gz"), Optimize::ShapeAndArea);
    eprintln!("hand: {:?}, d_face_rel {:.4}, faces {}", rep.shape, rep.quality.d_face_relative, out.faces.len());
    assert!(rep.shape.rebalance_collapses > 0 && rep.shape.rebalance_splits > 0, "{:?}", rep.shape);
    assert!(rep.quality.d_face_relative <= 0.03, "d_face_rel {:.4}", rep.quality.d_face_relative);
    assert!(angle_quality(&out).mean_min_angle_deg >= 48.0, "{:?}", angle_quality(&out));
    // A start is judged on its faces as they end: a sliver the untangling left and the last
    // moves for angles mended does not count. Counted before those moves, the hand's first
    // sample (mean smallest angle 49.15, no face below 15 degrees) missed the bar and the
    // other two starts were remeshed too, the grid's kept (48.66).
    assert_eq!(rep.shape.uncross.slivers_after, faces_below(&out, 15.0), "{:?}", rep.shape.uncross);
    assert_eq!((rep.shape.starts, rep.shape.start), (1, capmesh::remesh::shape::Start::Sample), "{:?}", rep.shape);
}

/// The polish stops once converged (`ShapeOptions::polish_tolerance`): on the left ventricle
/// it stops before its last iteration but after the global area steps, and the remesh is
/// within a few percent of the one that runs every iteration (tolerance 0).
#[test]
fn the_polish_stops_once_converged() {
    let mesh = load("open_lv_endo_rabbit_chaste.obj.gz");
    let shape = capmesh::remesh::shape::ShapeOptions::default();
    let options = RemeshOptions::default();
    let (_, early) = remesh(&mesh, &options, &NoProgress).unwrap();
    let (_, full) = remesh(&mesh, &options.clone().with_shape(shape.with_polish_tolerance(0.0)), &NoProgress).unwrap();
    let (e, f) = (&early.quality, &full.quality);
    eprintln!("iterations {} / {}: d_face_rel {:.4} / {:.4}, mean smallest angle {:.2} / {:.2}", early.shape.iterations, full.shape.iterations, e.d_face_relative, f.d_face_relative, e.mean_min_angle_deg, f.mean_min_angle_deg);
    assert_eq!(full.shape.iterations, shape.relax_iterations + shape.polish_iterations);
    assert!((shape.relax_iterations + 5 * shape.area_steps..full.shape.iterations).contains(&early.shape.iterations), "{} iterations", early.shape.iterations);
    assert!(e.d_face_relative <= 1.1 * f.d_face_relative && (e.mean_min_angle_deg - f.mean_min_angle_deg).abs() < 0.3, "{e:?} against {f:?}");
}

/// Shape options out of range set from Rust are refused by `remesh` with the field named,
/// before any work: a NaN crease bound used to find no crease and refuse no flip, silently.
#[test]
fn shape_options_out_of_range_are_refused() {
    use capmesh::remesh::shape::ShapeOptions;
    use capmesh::{Error, Sizing};
    let mesh = load("open_meg_helmet_babysquid_mne.obj.gz");
    let default = ShapeOptions::default();
    assert_eq!(default.check(), Ok(()));
    for (shape, named) in [
        (default.with_crease_deg(f64::NAN), "crease_deg = NaN"),
        (default.with_crease_deg(180.0), "crease_deg = 180"),
        (default.with_shape_weight(f64::INFINITY), "shape_weight = inf"),
        (default.with_polish_tolerance(f64::NAN), "polish_tolerance = NaN"),
        (default.with_sizing(Sizing::Curvature { strength: -2.0 }), "strength = -2"),
    ] {
        let options = RemeshOptions::default().with_shape(shape);
        match remesh(&mesh, &options, &NoProgress) {
            Err(Error::InvalidOption(message)) => assert!(message.contains(named), "{named}: {message}"),
            other => panic!("{named}: {:?}", other.map(|(_, r)| r.quality.faces)),
        }
    }
    // The negative tolerance the docs allow (every polish iteration runs) passes.
    assert_eq!(default.with_polish_tolerance(-1.0).check(), Ok(()));
}
