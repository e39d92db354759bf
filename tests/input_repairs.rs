//! The repairs `remesh` makes instead of refusing an input, as marching cubes leaves them:
//! surfaces that touch themselves at a vertex (pinched: the vertex's faces form several fans)
//! have such vertices split, one per fan (the parameterization splits those welding makes);
//! a surface with specks beside it is remeshed without them; faces wound against their
//! neighbours are flipped.

use capmesh::io::read_mesh;
use capmesh::mesh::repair::{orient_coherently, remove_duplicate_faces, split_pinched_vertices};
use capmesh::mesh::{validate, MeshError, SurfaceKind, TriMesh};
use capmesh::param::{parameterize, ParamOptions};
use capmesh::progress::NoProgress;
use capmesh::remesh::{remesh, CapGrid, RemeshOptions};

mod common;

/// The vertices within `rings` edges of `a`.
fn near(faces: &[[u32; 3]], n: usize, a: usize, rings: usize) -> Vec<bool> {
    let mut within = vec![false; n];
    within[a] = true;
    for _ in 0..rings {
        let grown: Vec<u32> = faces.iter().filter(|f| f.iter().any(|&v| within[v as usize])).flatten().copied().collect();
        for v in grown {
            within[v as usize] = true;
        }
    }
    within
}

/// The bundled closed hippocampus pinched: the closest pair of vertices more than 8 edges
/// apart on the surface (the two sides of a thin part) moved to their midpoint and made one
/// vertex. The other index is left unreferenced.
fn pinched_hippocampus() -> TriMesh {
    let mut m = read_mesh(&common::data("closed_hippocampus_choi.obj")).unwrap();
    let n = m.vertices.len();
    let d = |a: usize, b: usize| (0..3).map(|k| (m.vertices[a][k] - m.vertices[b][k]).powi(2)).sum::<f64>();
    // Candidates: every 25th vertex, against all vertices outside its 8 rings.
    let mut best = (f64::INFINITY, 0, 0);
    for a in (0..n).step_by(25) {
        let within = near(&m.faces, n, a, 8);
        for b in (0..n).filter(|&b| !within[b]) {
            if d(a, b) < best.0 {
                best = (d(a, b), a, b);
            }
        }
    }
    let (_, a, b) = best;
    let mid = std::array::from_fn(|k| 0.5 * (m.vertices[a][k] + m.vertices[b][k]));
    m.vertices[a] = mid;
    m.vertices[b] = mid;
    for f in &mut m.faces {
        for v in f.iter_mut() {
            if *v == b as u32 {
                *v = a as u32;
            }
        }
    }
    m
}

#[test]
fn a_pinched_closed_surface_is_split_and_remeshed() {
    let m = pinched_hippocampus();
    assert!(matches!(validate(&m), Err(MeshError::NonManifoldVertex { fans: 2, .. })), "the test mesh must be pinched");
    let (out, rep) = remesh(&m, &RemeshOptions::default().with_grid(CapGrid::Uniform { faces: 5000 }), &NoProgress).unwrap();
    assert_eq!(rep.split_vertices, 1);
    let (kind, _) = validate(&out).unwrap();
    assert_eq!(kind, SurfaceKind::ClosedSphere);
    let q = &rep.quality;
    eprintln!("pinched hippocampus: d_face_rel {:.4}, min angle {:.2}, mean min angle {:.2}", q.d_face_relative, q.min_angle_deg, q.mean_min_angle_deg);
    assert!(q.d_face_relative <= 0.035 && q.min_angle_deg >= 15.0 && q.mean_min_angle_deg >= 48.0, "{q:?}");
}

#[test]
fn a_pinch_made_by_welding_is_split_again() {
    // The split mesh has the copy at the same point: welding merges it back, and the
    // parameterization splits that pinch again.
    let split = split_pinched_vertices(&pinched_hippocampus()).unwrap();
    assert_eq!(split.copy_of.len(), 1);
    assert_eq!(split.mesh.vertices[split.copy_of[0] as usize], *split.mesh.vertices.last().unwrap());
    let map = parameterize(&split.mesh, &ParamOptions::default(), &NoProgress).unwrap();
    // Welded: the copy and the unreferenced vertex left at the same point.
    assert_eq!((map.report.welded_vertices, map.report.split_vertices), (2, 1));
    assert!(map.report.area_distortion.mean_abs < 0.05, "{}", map.report.area_distortion.mean_abs);
    // The copy keeps its own point of the map: the faces of both fans stay unfolded.
    assert_eq!(map.report.flipped_faces, 0);
    let c = split.mesh.vertices.len() - 1;
    assert_ne!(map.plane[c], map.plane[split.copy_of[0] as usize]);
}

#[test]
fn the_command_line_splits_a_pinched_input() {
    let dir = common::TempDir::new("repairs");
    let input = dir.path("pinched.obj");
    capmesh::io::write_mesh(&input, &pinched_hippocampus()).unwrap();
    let check = common::cli::capmesh().arg("check").arg(&input).output().unwrap();
    let text = String::from_utf8_lossy(&check.stdout);
    assert!(check.status.success() && text.contains("pinched vertices     split, 1 copies") && text.contains("closed genus-0"), "{text}");
    let report = dir.path("r.json");
    let run = common::cli::capmesh().args(["remesh", "--faces", "2000", "-o"]).arg(dir.path("out.ply")).arg("--report").arg(&report).arg(&input).output().unwrap();
    let text = String::from_utf8_lossy(&run.stdout);
    assert!(run.status.success() && text.contains("touches itself") && text.contains("(1 copy appended)"), "{text}{}", String::from_utf8_lossy(&run.stderr));
    let json: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    assert_eq!(json["split_vertices"], 1);
}

/// The bundled bunny with `piece` added as a separate piece (its vertices after the bunny's).
fn bunny_with(piece: &TriMesh) -> (TriMesh, usize) {
    let mut m = read_mesh(&common::data("closed_bunny_npm.obj")).unwrap();
    let (offset, faces) = (m.vertices.len() as u32, m.faces.len());
    m.vertices.extend(piece.vertices.iter().copied());
    m.faces.extend(piece.faces.iter().map(|f| f.map(|v| v + offset)));
    (m, faces)
}

/// A speck: an icosphere of `radius` at `centre`.
fn speck(radius: f64, centre: [f64; 3]) -> TriMesh {
    let s = capmesh::mesh::shapes::icosphere(1);
    TriMesh::new(s.vertices.iter().map(|p| std::array::from_fn(|k| centre[k] + radius * p[k])).collect(), s.faces)
}

#[test]
fn specks_beside_a_surface_are_dropped_and_reported() {
    let bunny = read_mesh(&common::data("closed_bunny_npm.obj")).unwrap();
    let diagonal = bunny.bounding_box_diagonal();
    let (m, bunny_faces) = bunny_with(&speck(0.01 * diagonal, [0.0, 0.0, 0.0]));
    assert!(matches!(validate(&m), Err(MeshError::SeveralComponents { count: 2 })));
    let options = RemeshOptions::default().with_grid(CapGrid::Uniform { faces: 3000 });
    let (out, rep, points) = capmesh::remesh::remesh_located(&m, &options, &NoProgress).unwrap();
    assert_eq!(rep.dropped_components, 1);
    assert!(rep.dropped_area_share > 0.0 && rep.dropped_area_share <= capmesh::remesh::DROPPED_AREA_SHARE, "{}", rep.dropped_area_share);
    assert_eq!(validate(&out).unwrap().0, SurfaceKind::ClosedSphere);
    // Surface points name the input's faces: all on the bunny's.
    assert!(points.iter().all(|p| p.face < bunny_faces));
    // The same remesh as the bunny alone (the speck's vertices only left unreferenced).
    let (alone, _) = remesh(&bunny, &options, &NoProgress).unwrap();
    assert_eq!(out, alone);
}

#[test]
fn a_second_surface_of_its_own_size_is_an_error_unless_the_largest_piece_is_asked_for() {
    let bunny = read_mesh(&common::data("closed_bunny_npm.obj")).unwrap();
    let diagonal = bunny.bounding_box_diagonal();
    let (m, _) = bunny_with(&speck(0.2 * diagonal, [2.0 * diagonal, 0.0, 0.0]));
    let err = remesh(&m, &RemeshOptions::default(), &NoProgress).unwrap_err();
    assert!(err.to_string().contains("2 connected components") && err.to_string().contains("--largest-piece"), "{err}");
    // Asked for, the largest piece is remeshed alone, as it would be on its own.
    let options = RemeshOptions::default().with_grid(CapGrid::Uniform { faces: 2000 }).with_pieces(capmesh::Pieces::Largest);
    let (out, rep) = remesh(&m, &options, &NoProgress).unwrap();
    let main = capmesh::mesh::repair::keep_main_component(&m).unwrap();
    assert!(rep.dropped_components == 1 && rep.dropped_area_share > capmesh::remesh::DROPPED_AREA_SHARE, "{rep:?}");
    assert_eq!(out, remesh(&main.mesh, &options, &NoProgress).unwrap().0);
    // The command line's --largest-piece.
    let dir = common::TempDir::new("largest");
    let input = dir.path("two.obj");
    capmesh::io::write_mesh(&input, &m).unwrap();
    let run = common::cli::capmesh().arg("remesh").arg(&input).args(["--faces", "2000", "--quiet", "--largest-piece", "-o"]).arg(dir.path("out.obj")).output().unwrap();
    assert!(run.status.success() && String::from_utf8_lossy(&run.stdout).contains("remeshed the largest piece; dropped 1 other piece"), "{}{}", String::from_utf8_lossy(&run.stdout), String::from_utf8_lossy(&run.stderr));
}

/// Each remesh vertex's surface point is the weights times the corners of `input`'s face, and
/// the vertex lies near it (fitted off the surface by a fraction of an edge).
fn assert_points_on_input_corners(input: &TriMesh, out: &TriMesh, points: &[capmesh::cap::SurfacePoint]) {
    let tolerance = 1e-9 * input.bounding_box_diagonal();
    for (p, x) in points.iter().zip(&out.vertices) {
        let f = input.faces[p.face];
        let q: [f64; 3] = std::array::from_fn(|k| (0..3).map(|c| p.barycentric[c] * input.vertices[f[c] as usize][k]).sum());
        assert!((0..3).all(|k| (q[k] - p.position[k]).abs() <= tolerance), "{q:?} against {:?}", p.position);
        assert!((0..3).all(|k| (q[k] - x[k]).abs() <= 0.02 * input.bounding_box_diagonal()), "{q:?} against {x:?}");
    }
}

/// The bundled closed hippocampus with every seventh face wound the other way (its second and
/// third corners swapped, so that the repair gives back the very faces).
fn misoriented_hippocampus() -> (TriMesh, TriMesh, usize) {
    let m = read_mesh(&common::data("closed_hippocampus_choi.obj")).unwrap();
    let mut bad = m.clone();
    let mut flipped = 0;
    for f in bad.faces.iter_mut().step_by(7) {
        f.swap(1, 2);
        flipped += 1;
    }
    (m, bad, flipped)
}

#[test]
fn faces_wound_against_their_neighbours_are_flipped_back() {
    let (good, bad, flipped) = misoriented_hippocampus();
    assert!(matches!(validate(&bad), Err(MeshError::InconsistentOrientation { .. })));
    let o = orient_coherently(&bad).unwrap();
    assert_eq!(o.flipped_faces, flipped);
    assert_eq!(validate(&o.mesh).unwrap().0, SurfaceKind::ClosedSphere);
    // Each flipped face walks its corners the good mesh's way round.
    assert_eq!(o.mesh, good);
    assert_eq!(o.flipped.iter().enumerate().filter(|(_, &x)| x).map(|(t, _)| t % 7).max(), Some(0));
    // The majority is kept: the whole mesh turned inside out flips nothing back.
    let inward = TriMesh::new(good.vertices.clone(), good.faces.iter().map(|f| [f[0], f[2], f[1]]).collect());
    assert!(orient_coherently(&inward).is_none());
    // A Moebius strip (five triangles (i, i+1, i+2) mod 5) cannot be oriented.
    let strip = TriMesh::new(
        (0..5).map(|k| { let t = k as f64 * 0.4 * std::f64::consts::PI; [t.cos(), t.sin(), 0.1 * k as f64] }).collect(),
        (0..5u32).map(|i| [i, (i + 1) % 5, (i + 2) % 5]).collect(),
    );
    assert!(orient_coherently(&strip).is_none());
}

#[test]
fn remesh_flips_misoriented_faces_and_reports_them() {
    let (good, bad, flipped) = misoriented_hippocampus();
    let options = RemeshOptions::default().with_grid(CapGrid::Uniform { faces: 2000 });
    let (out, rep, points) = capmesh::remesh::remesh_located(&bad, &options, &NoProgress).unwrap();
    assert_eq!(rep.reoriented_faces, flipped);
    // The same remesh as the coherent input's.
    let (alone, _) = remesh(&good, &options, &NoProgress).unwrap();
    assert_eq!(out, alone);
    // Surface points weigh the input's own corners, in its order.
    assert_points_on_input_corners(&bad, &out, &points);
    // The command line says so and writes it into the report.
    let dir = common::TempDir::new("misoriented");
    let input = dir.path("hippocampus_misoriented.obj");
    capmesh::io::write_mesh(&input, &bad).unwrap();
    let report = dir.path("report.json");
    let run = common::cli::capmesh().arg("remesh").arg(&input).args(["--faces", "2000", "--quiet", "-o"]).arg(dir.path("out.obj")).arg("--report").arg(&report).output().unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    assert!(String::from_utf8_lossy(&run.stdout).contains(&format!("{flipped} faces wound against their neighbours")), "{}", String::from_utf8_lossy(&run.stdout));
    let json: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    assert_eq!(json["reoriented_faces"], flipped);
    // `capmesh param` maps the repaired input and writes its faces.
    let out = dir.path("cap.obj");
    let run = common::cli::capmesh().arg("param").arg(&input).args(["--quiet", "-o"]).arg(&out).output().unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    assert!(String::from_utf8_lossy(&run.stdout).contains("wound against their neighbours"), "{}", String::from_utf8_lossy(&run.stdout));
    assert_eq!(read_mesh(&out).unwrap().faces, good.faces);
    // `capmesh check` counts them and passes.
    let check = common::cli::capmesh().arg("check").arg(&input).output().unwrap();
    let text = String::from_utf8_lossy(&check.stdout);
    assert!(check.status.success() && text.contains(&format!("misoriented faces    flipped, {flipped}")) && text.contains("closed genus-0"), "{text}");
}

#[test]
fn repeated_faces_are_dropped_by_remesh() {
    let good = read_mesh(&common::data("closed_hippocampus_choi.obj")).unwrap();
    // Three repeats: one as is, one rotated, one wound the other way (a flap), placed
    // among the faces so that the later faces are renumbered.
    let mut bad = good.clone();
    for (at, f) in [(10, good.faces[3]), (500, [good.faces[77][1], good.faces[77][2], good.faces[77][0]]), (2000, [good.faces[900][0], good.faces[900][2], good.faces[900][1]])] {
        bad.faces.insert(at, f);
    }
    assert!(matches!(validate(&bad), Err(MeshError::DuplicateFace { .. })));
    let d = remove_duplicate_faces(&bad).unwrap();
    assert_eq!((d.removed_faces, &d.mesh), (3, &good));
    assert!(remove_duplicate_faces(&good).is_none());
    let options = RemeshOptions::default().with_grid(CapGrid::Uniform { faces: 2000 });
    let (out, rep, points) = capmesh::remesh::remesh_located(&bad, &options, &NoProgress).unwrap();
    assert_eq!(rep.duplicate_faces, 3);
    let (alone, _) = remesh(&good, &options, &NoProgress).unwrap();
    assert_eq!(out, alone);
    // Surface points name the faces of the input as given (with its repeats).
    assert_points_on_input_corners(&bad, &out, &points);
}

/// `repair_for` (the one dispatch of remesh, param and check) picks the repair that mends
/// each validation error, and none for errors no repair mends.
#[test]
fn each_validation_error_gets_its_repair() {
    use capmesh::mesh::repair::{repair_for, Repaired};
    let (good, bad, flipped) = misoriented_hippocampus();
    let e = validate(&bad).unwrap_err();
    match repair_for(&bad, &e).unwrap() {
        Some(Repaired::Reoriented(o)) => assert_eq!((o.flipped_faces, &o.mesh), (flipped, &good)),
        other => panic!("misoriented faces got {other:?}"),
    }
    let mut repeated = good.clone();
    repeated.faces.push(good.faces[5]);
    let e = validate(&repeated).unwrap_err();
    match repair_for(&repeated, &e).unwrap() {
        Some(Repaired::Deduplicated(d)) => assert_eq!((d.removed_faces, &d.mesh), (1, &good)),
        other => panic!("a repeated face got {other:?}"),
    }
    let pinched = pinched_hippocampus();
    let e = validate(&pinched).unwrap_err();
    assert!(matches!(e, MeshError::NonManifoldVertex { .. }), "{e}");
    match repair_for(&pinched, &e).unwrap() {
        Some(Repaired::Split(s)) => {
            assert!(!s.copy_of.is_empty());
            assert_eq!(validate(&s.mesh).unwrap().0, SurfaceKind::ClosedSphere);
        }
        other => panic!("a pinched vertex got {other:?}"),
    }
    // An error no repair mends, and a repair with nothing to do, leave the error standing.
    let mut fin = good.clone();
    let [a, b, _] = good.faces[0];
    fin.faces.push([a, b, good.faces[good.faces.len() / 2][0]]);
    let e = validate(&fin).unwrap_err();
    assert!(repair_for(&fin, &e).unwrap().is_none(), "{e}");
    assert!(repair_for(&good, &MeshError::DuplicateFace { face: 1, first: 0 }).is_ok_and(|r| r.is_none()));
}

/// A closed surface missing one face is mapped as a disk (it is one), and check, param and
/// remesh say that its boundary is tiny for its size; a genuine open surface gets no such note.
#[test]
fn a_closed_surface_with_a_hole_is_pointed_out() {
    use capmesh::mesh::validate::{small_boundary, SMALL_BOUNDARY};
    let good = read_mesh(&common::data("closed_hippocampus_choi.obj")).unwrap();
    let holed = TriMesh::new(good.vertices.clone(), good.faces[1..].to_vec());
    assert_eq!(validate(&holed).unwrap().0, SurfaceKind::OpenDisk);
    let (edges, ratio) = small_boundary(&holed).unwrap();
    assert_eq!(edges, 3);
    assert!(ratio > 0.0 && ratio < SMALL_BOUNDARY, "{ratio}");
    // The ratio is the triangle's perimeter over the root of the remaining area.
    let [a, b, c] = good.faces[0].map(|v| good.vertices[v as usize]);
    let d = |p: [f64; 3], q: [f64; 3]| (0..3).map(|k| (p[k] - q[k]).powi(2)).sum::<f64>().sqrt();
    let area: f64 = holed.faces.iter().map(|f| capmesh::mesh::geometry::triangle_area(holed.vertices[f[0] as usize], holed.vertices[f[1] as usize], holed.vertices[f[2] as usize])).sum();
    assert!((ratio - (d(a, b) + d(b, c) + d(c, a)) / area.sqrt()).abs() < 1e-12 * ratio);
    for open in ["open_face_choi.obj", "open_lv_endo_rabbit_chaste.obj", "open_hand_choi.obj"] {
        assert!(small_boundary(&read_mesh(&common::data(open)).unwrap()).is_none(), "{open}");
    }
    assert!(small_boundary(&good).is_none());
    let dir = common::TempDir::new("holed");
    let input = dir.path("holed.obj");
    capmesh::io::write_mesh(&input, &holed).unwrap();
    let note = "a closed surface with a hole?";
    for args in [vec!["check"], vec!["param", "--quiet", "-o", "cap.obj"], vec!["remesh", "--quiet", "--faces", "1000", "-o", "re.obj"]] {
        let out = common::cli::capmesh().current_dir(dir.path(".")).arg(args[0]).arg(&input).args(&args[1..]).output().unwrap();
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(out.status.success() && text.contains(note) && text.contains("(3 edges)"), "{args:?}: {text}");
    }
    let out = common::cli::capmesh().arg("check").arg(common::data("open_face_choi.obj")).output().unwrap();
    assert!(!String::from_utf8_lossy(&out.stdout).contains(note));
}
