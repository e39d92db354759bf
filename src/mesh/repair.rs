//! Small, safe repairs: welding coincident vertices, dropping unreferenced vertices, finding
//! zero-area faces, splitting pinched vertices, removing duplicate faces, orienting faces
//! coherently and keeping the largest piece.
//!
//! Welding uses a uniform grid of cell size `tolerance` (hashing the cells), so it is linear in
//! the number of vertices. Each grid cell keeps only cluster *representatives*: a vertex within
//! `tolerance` of a representative joins its cluster, otherwise it becomes a representative.
//! This bounds the work even when millions of vertices sit on the same spot, and keeps every
//! merged vertex within `tolerance` of a representative (no unbounded chaining).

use crate::mesh::fasthash::FastMap;
use crate::mesh::geometry::{cross, dot, norm, sub};
use crate::mesh::unionfind::UnionFind;
use crate::mesh::checks::{check_degenerate, check_duplicates, check_indices, check_not_empty};
use crate::mesh::topology::{corner_fans, edge_faces, face_neighbours};
use crate::mesh::{MeshError, TriMesh};

/// `old_to_new` value of a vertex that was removed (unreferenced after the repair).
pub const REMOVED: u32 = u32::MAX;

/// Default relative tolerance of [`zero_area_faces`].
pub const DEFAULT_ZERO_AREA_REL_TOL: f64 = 1e-12;

/// Default welding tolerance relative to the bounding-box diagonal.
pub const DEFAULT_WELD_REL_TOL: f64 = 1e-9;

/// Result of [`weld_coincident`] (or [`remove_unreferenced`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Welded {
    /// The repaired mesh.
    pub mesh: TriMesh,
    /// For each input vertex, its index in `mesh`, or [`REMOVED`] if it was dropped because no
    /// face uses it (merged vertices map to the vertex they were merged into).
    pub old_to_new: Vec<u32>,
    /// Number of input vertices merged into another vertex.
    pub merged_vertices: usize,
    /// Number of faces dropped: faces that became degenerate (a repeated vertex) after merging,
    /// and faces with an out-of-range vertex index.
    pub removed_faces: usize,
    /// Number of (merged) vertices dropped because no face uses them.
    pub removed_unreferenced: usize,
    /// Copies made of pinched vertices, one per fan beyond the first (0 from
    /// [`weld_coincident`]; the parameterization splits the pinches welding makes).
    pub split_vertices: usize,
}

/// `DEFAULT_WELD_REL_TOL` times the bounding-box diagonal (0 for an empty mesh).
pub fn default_weld_tolerance(mesh: &TriMesh) -> f64 {
    DEFAULT_WELD_REL_TOL * mesh.bounding_box_diagonal()
}

/// Merge vertices closer than `tolerance` (Euclidean distance `<= tolerance`), drop faces that
/// become degenerate, drop unreferenced vertices. Face order and the relative order of the kept
/// vertices are preserved; a merged vertex takes the position of the smallest index in its
/// cluster.
///
/// A `tolerance` that is zero, negative or not finite merges only exactly equal positions.
/// Vertices with non-finite coordinates are never merged. Faces with out-of-range indices are
/// dropped (counted in `removed_faces`); run [`crate::mesh::validate()`] first to report them.
pub fn weld_coincident(mesh: &TriMesh, tolerance: f64) -> Welded {
    let rep = representatives(&mesh.vertices, tolerance);
    compact(mesh, &rep, true)
}

/// Number of vertices that [`weld_coincident`] would merge into another vertex with this
/// `tolerance` (for 14 coincident pairs: 14).
pub fn coincident_vertices(mesh: &TriMesh, tolerance: f64) -> usize {
    representatives(&mesh.vertices, tolerance)
        .iter()
        .enumerate()
        .filter(|&(v, &r)| r as usize != v)
        .count()
}

/// Drop vertices that no face uses (faces are kept as they are, except faces with an
/// out-of-range index, which are dropped).
pub fn remove_unreferenced(mesh: &TriMesh) -> Welded {
    let rep: Vec<u32> = (0..mesh.n_vertices() as u32).collect();
    compact(mesh, &rep, false)
}

/// Indices of faces whose area is at most `rel_tol` times the square of their longest edge
/// (collinear or coincident corners; the test is scale-invariant). Faces with an out-of-range
/// index are skipped; faces with non-finite area are included.
pub fn zero_area_faces(mesh: &TriMesh, rel_tol: f64) -> Vec<usize> {
    let n = mesh.n_vertices();
    mesh.faces
        .iter()
        .enumerate()
        .filter(|(_, f)| f.iter().all(|&v| (v as usize) < n))
        .filter(|(_, f)| {
            let [a, b, c] = [0, 1, 2].map(|k| mesh.vertices[f[k] as usize]);
            let (ab, bc, ca) = (sub(b, a), sub(c, b), sub(a, c));
            let longest2 = dot(ab, ab).max(dot(bc, bc)).max(dot(ca, ca));
            let area = 0.5 * norm(cross(ab, sub(c, a)));
            // NaN areas count as zero-area (not `area <= ...`, which is false for NaN).
            area.partial_cmp(&(rel_tol * longest2)) != Some(std::cmp::Ordering::Greater)
        })
        .map(|(i, _)| i)
        .collect()
}

/// Grid cell (or exact bit pattern) key of a point.
fn cell_key(p: [f64; 3], cell: Option<f64>) -> [i64; 3] {
    match cell {
        // `as` saturates, so huge ratios cannot overflow; the cell size is bounded below so
        // that the ratios stay well inside the i64 range anyway.
        Some(h) => p.map(|x| (x / h).floor() as i64),
        // +0.0 and -0.0 are equal positions.
        None => p.map(|x| if x == 0.0 { 0 } else { x.to_bits() as i64 }),
    }
}

/// For every vertex, the smallest vertex index of its cluster.
fn representatives(vertices: &[[f64; 3]], tolerance: f64) -> Vec<u32> {
    let n = vertices.len().min(u32::MAX as usize);
    let mut uf = UnionFind::new(n);
    let exact = !(tolerance > 0.0 && tolerance.is_finite());
    let max_abs = vertices
        .iter()
        .flatten()
        .filter(|x| x.is_finite())
        .fold(0.0f64, |m, x| m.max(x.abs()));
    // Keep |x / cell| below 2^50 so that cell indices are exact and neighbours do not overflow.
    let cell = (!exact).then(|| tolerance.max(max_abs * 2f64.powi(-50)));
    let tol2 = tolerance * tolerance;
    const NONE: u32 = u32::MAX;
    let mut head: FastMap<[i64; 3], u32> = FastMap::default();
    head.reserve(n);
    let mut next_rep = vec![NONE; n];

    for v in 0..n {
        let p = vertices[v];
        if !p.iter().all(|x| x.is_finite()) {
            continue;
        }
        let key = cell_key(p, cell);
        let mut merged = false;
        if exact {
            if let Some(&r) = head.get(&key) {
                uf.union(v as u32, r);
                merged = true;
            }
        } else {
            for dx in -1i64..=1 {
                for dy in -1i64..=1 {
                    for dz in -1i64..=1 {
                        let k = [
                            key[0].saturating_add(dx),
                            key[1].saturating_add(dy),
                            key[2].saturating_add(dz),
                        ];
                        let mut r = head.get(&k).copied().unwrap_or(NONE);
                        while r != NONE {
                            let d = sub(p, vertices[r as usize]);
                            if dot(d, d) <= tol2 {
                                uf.union(v as u32, r);
                                merged = true;
                            }
                            r = next_rep[r as usize];
                        }
                    }
                }
            }
        }
        if !merged {
            let old = head.insert(key, v as u32).unwrap_or(NONE);
            next_rep[v] = old;
        }
    }

    let mut min_of_root = vec![NONE; n];
    let mut rep = Vec::with_capacity(vertices.len());
    for v in 0..n {
        let r = uf.find(v as u32) as usize;
        if min_of_root[r] == NONE {
            min_of_root[r] = v as u32;
        }
        rep.push(min_of_root[r]);
    }
    // Vertices beyond u32 range cannot be referenced by a face; keep them as themselves.
    rep.extend((n..vertices.len()).map(|_| NONE));
    rep
}

/// The input faces that welding kept, in order (the welded mesh's faces are these, remapped):
/// those whose three vertices are kept and distinct under `old_to_new`.
pub(crate) fn kept_faces<'a>(mesh: &'a TriMesh, old_to_new: &'a [u32]) -> impl Iterator<Item = usize> + 'a {
    mesh.faces.iter().enumerate().filter_map(move |(f, face)| {
        let [a, b, c] = face.map(|v| old_to_new.get(v as usize).copied().unwrap_or(REMOVED));
        (a != REMOVED && b != REMOVED && c != REMOVED && a != b && b != c && a != c).then_some(f)
    })
}

/// Result of [`split_pinched_vertices`].
#[derive(Debug, Clone, PartialEq)]
pub struct Split {
    /// The mesh with one vertex per fan: the input's vertices in their order, then one copy
    /// per extra fan of a pinched vertex; the faces in their order (those of an extra fan
    /// use its copy).
    pub mesh: TriMesh,
    /// For each appended copy (vertex `n + k` of `mesh`, `n` the input's vertex count), the
    /// input vertex it copies.
    pub copy_of: Vec<u32>,
}

/// Split every pinched vertex (its faces form several fans: the surface touches itself at
/// that point, as marching cubes leaves where a segmentation's folds meet) into one vertex
/// per fan, all at the same position: MeshLab's "Split Vertices on Non Manifold Vertices".
/// The first fan met in face order keeps the vertex. A closed surface pinched at `k`
/// vertices has Euler characteristic 2 again after the split when it was a sphere touching
/// itself. Fails as [`Topology::build`](crate::mesh::Topology::build) does on anything else
/// that is not a manifold (non-manifold edges, inconsistent orientation, ...).
pub fn split_pinched_vertices(mesh: &TriMesh) -> Result<Split, MeshError> {
    check_not_empty(mesh)?;
    check_indices(mesh)?;
    check_degenerate(mesh)?;
    check_duplicates(mesh)?;
    let edges = edge_faces(mesh)?;
    let mut fans = corner_fans(mesh, &edges);
    const UNSET: u32 = u32::MAX;
    let n = mesh.n_vertices();
    let mut first_fan = vec![UNSET; n];
    // The copy made for each fan's root corner (`UNSET`: none yet).
    let mut copy_for_fan = vec![UNSET; 3 * mesh.n_faces()];
    let mut vertices = mesh.vertices.clone();
    let mut faces = mesh.faces.clone();
    let mut copy_of = Vec::new();
    for (f, face) in faces.iter_mut().enumerate() {
        for (k, v) in face.iter_mut().enumerate() {
            let fan = fans.find((3 * f + k) as u32);
            let first = &mut first_fan[*v as usize];
            if *first == UNSET {
                *first = fan;
            } else if *first != fan {
                let copy = &mut copy_for_fan[fan as usize];
                if *copy == UNSET {
                    *copy = vertices.len() as u32;
                    vertices.push(vertices[*v as usize]);
                    copy_of.push(*v);
                }
                *v = *copy;
            }
        }
    }
    Ok(Split { mesh: TriMesh::new(vertices, faces), copy_of })
}

/// A repair made for a validation error by [`repair_for`].
#[derive(Debug, Clone, PartialEq)]
pub enum Repaired {
    /// Pinched vertices split ([`split_pinched_vertices`]).
    Split(Split),
    /// Repeated faces dropped ([`remove_duplicate_faces`]).
    Deduplicated(Deduplicated),
    /// Faces flipped to agree with their neighbours ([`orient_coherently`]).
    Reoriented(Reoriented),
}

/// The repair that mends what `error` (from [`crate::mesh::validate()`] of `mesh`) refuses, as
/// `param`, `remesh` and `check` make it: pinched vertices split
/// ([`MeshError::NonManifoldVertex`]), repeated faces dropped ([`MeshError::DuplicateFace`]),
/// faces wound against their neighbours flipped ([`MeshError::InconsistentOrientation`]).
/// `Ok(None)` for any other error or when the repair finds nothing to do (the error stands);
/// `Err` when splitting meets a worse defect (a non-manifold edge), which it names.
pub fn repair_for(mesh: &TriMesh, error: &MeshError) -> Result<Option<Repaired>, MeshError> {
    Ok(match error {
        MeshError::NonManifoldVertex { .. } => Some(split_pinched_vertices(mesh)?).filter(|s| !s.copy_of.is_empty()).map(Repaired::Split),
        MeshError::DuplicateFace { .. } => remove_duplicate_faces(mesh).map(Repaired::Deduplicated),
        MeshError::InconsistentOrientation { .. } => orient_coherently(mesh).map(Repaired::Reoriented),
        _ => None,
    })
}

/// Result of [`remove_duplicate_faces`].
#[derive(Debug, Clone, PartialEq)]
pub struct Deduplicated {
    /// The mesh without the later copies; vertices unchanged, faces in their order.
    pub mesh: TriMesh,
    /// The input face of each kept face.
    pub faces: Vec<u32>,
    /// Faces removed.
    pub removed_faces: usize,
}

/// Drop every face that uses the same three vertices as an earlier one, in any order (an
/// exporter's repeated faces, or a flap wound both ways), as MeshLab's "Remove Duplicate
/// Faces" does; `None` when there is none.
pub fn remove_duplicate_faces(mesh: &TriMesh) -> Option<Deduplicated> {
    let mut seen: FastMap<[u32; 3], ()> = FastMap::default();
    let mut faces = Vec::with_capacity(mesh.n_faces());
    for (t, f) in mesh.faces.iter().enumerate() {
        if seen.insert(super::topology::sorted_face(*f), ()).is_none() {
            faces.push(t as u32);
        }
    }
    let removed_faces = mesh.n_faces() - faces.len();
    (removed_faces > 0).then(|| Deduplicated {
        mesh: TriMesh::new(mesh.vertices.clone(), faces.iter().map(|&t| mesh.faces[t as usize]).collect()),
        faces,
        removed_faces,
    })
}

/// Result of [`orient_coherently`].
#[derive(Debug, Clone, PartialEq)]
pub struct Reoriented {
    /// The mesh with each flipped face's second and third corners swapped; the vertices and
    /// the order of the faces unchanged.
    pub mesh: TriMesh,
    /// Whether each face was flipped.
    pub flipped: Vec<bool>,
    /// How many faces were flipped.
    pub flipped_faces: usize,
}

/// Flip faces so that every edge is walked once in each direction, as MeshLab's "Re-Orient all
/// faces coherently" does (exported or hand-edited meshes come with some faces wound the
/// other way). Each piece (faces joined through edges) keeps the orientation of the majority
/// of its faces, the first face's on a tie. `None` when no face needs a flip, or when the
/// mesh cannot be oriented (an edge with more than two faces, a one-sided piece such as a
/// Moebius strip, an out-of-range index or a repeated vertex): validation then says why.
pub fn orient_coherently(mesh: &TriMesh) -> Option<Reoriented> {
    if check_indices(mesh).is_err() || check_degenerate(mesh).is_err() {
        return None;
    }
    let faces = &mesh.faces;
    let neighbours = face_neighbours(mesh)?;
    // Per face: unseen, kept (false) or flipped (true).
    let mut flip: Vec<Option<bool>> = vec![None; faces.len()];
    let mut stack = Vec::new();
    for start in 0..faces.len() {
        if flip[start].is_some() {
            continue;
        }
        flip[start] = Some(false);
        stack.push(start);
        let mut piece = Vec::new();
        while let Some(t) = stack.pop() {
            piece.push(t);
            let flipped = flip[t] == Some(true);
            for &(g, same) in neighbours[t].iter().flatten() {
                let g = g as usize;
                // Face t walks its edge one way (flipped: the other); g must walk it the
                // other way.
                let needed = same != flipped;
                match flip[g] {
                    None => {
                        flip[g] = Some(needed);
                        stack.push(g);
                    }
                    Some(f) if f != needed => return None,
                    Some(_) => {}
                }
            }
        }
        let flipped = piece.iter().filter(|&&t| flip[t] == Some(true)).count();
        if 2 * flipped > piece.len() {
            for &t in &piece {
                flip[t] = flip[t].map(|f| !f);
            }
        }
    }
    let flipped: Vec<bool> = flip.into_iter().map(|f| f == Some(true)).collect();
    let flipped_faces = flipped.iter().filter(|&&f| f).count();
    if flipped_faces == 0 {
        return None;
    }
    let faces = faces.iter().zip(&flipped).map(|(f, &x)| if x { [f[0], f[2], f[1]] } else { *f }).collect();
    Some(Reoriented { mesh: TriMesh::new(mesh.vertices.clone(), faces), flipped, flipped_faces })
}

/// Result of [`keep_main_component`].
#[derive(Debug, Clone, PartialEq)]
pub struct MainComponent {
    /// The piece of largest area: its vertices and faces, each in the input's order (the
    /// other pieces' vertices dropped).
    pub mesh: TriMesh,
    /// The input face of each kept face.
    pub faces: Vec<u32>,
    /// Pieces dropped.
    pub dropped_components: usize,
    /// Their share of the input's area.
    pub dropped_area_share: f64,
}

/// The piece of largest area of a mesh made of several (faces joined through shared
/// vertices), as MeshLab's "Remove Isolated pieces" keeps it; `None` when the mesh is one
/// piece. Faces with out-of-range indices belong to no piece (validation reports them).
pub fn keep_main_component(mesh: &TriMesh) -> Option<MainComponent> {
    let n = mesh.n_vertices();
    let valid = |f: &[u32; 3]| f.iter().all(|&v| (v as usize) < n);
    let mut sets = UnionFind::new(n);
    for f in mesh.faces.iter().filter(|f| valid(f)) {
        sets.union(f[0], f[1]);
        sets.union(f[1], f[2]);
    }
    let mut area: FastMap<u32, f64> = FastMap::default();
    let mut root_of = Vec::with_capacity(mesh.n_faces());
    for f in &mesh.faces {
        let root = valid(f).then(|| sets.find(f[0]));
        if let Some(r) = root {
            let [a, b, c] = f.map(|v| mesh.vertices[v as usize]);
            *area.entry(r).or_insert(0.0) += 0.5 * norm(cross(sub(b, a), sub(c, a)));
        }
        root_of.push(root);
    }
    if area.len() < 2 {
        return None;
    }
    let total: f64 = area.values().sum();
    // The largest area; ties to the piece met first in face order.
    let main = root_of.iter().flatten().copied().fold(None, |best: Option<u32>, r| match best {
        Some(b) if area[&b] >= area[&r] => Some(b),
        _ => Some(r),
    })?;
    let faces: Vec<u32> = (0..mesh.n_faces() as u32).filter(|&t| root_of[t as usize] == Some(main)).collect();
    let kept = faces.iter().map(|&t| mesh.faces[t as usize]).collect();
    Some(MainComponent {
        mesh: remove_unreferenced(&TriMesh::new(mesh.vertices.clone(), kept)).mesh,
        faces,
        dropped_components: area.len() - 1,
        dropped_area_share: if total > 0.0 { 1.0 - area[&main] / total } else { 0.0 },
    })
}

/// Apply a vertex-to-representative map: remap faces (dropping degenerate ones if asked, and
/// always those with out-of-range indices), then drop unreferenced vertices.
pub(crate) fn compact(mesh: &TriMesh, rep: &[u32], drop_degenerate: bool) -> Welded {
    let n = mesh.n_vertices();
    let merged_vertices = rep
        .iter()
        .enumerate()
        .filter(|&(v, &r)| r != REMOVED && r as usize != v)
        .count();
    let mut faces = Vec::with_capacity(mesh.n_faces());
    let mut removed_faces = 0;
    let mut used = vec![false; n];
    for face in &mesh.faces {
        let mapped = face.map(|v| rep.get(v as usize).copied().unwrap_or(REMOVED));
        let [a, b, c] = mapped;
        let bad_index = mapped.iter().any(|&v| v == REMOVED || v as usize >= n);
        if bad_index || (drop_degenerate && (a == b || b == c || a == c)) {
            removed_faces += 1;
            continue;
        }
        for v in mapped {
            used[v as usize] = true;
        }
        faces.push(mapped);
    }
    let mut new_index = vec![REMOVED; n];
    let mut vertices = Vec::new();
    let mut removed_unreferenced = 0;
    for v in 0..n {
        if rep[v] as usize == v {
            if used[v] {
                new_index[v] = vertices.len() as u32;
                vertices.push(mesh.vertices[v]);
            } else {
                removed_unreferenced += 1;
            }
        }
    }
    let old_to_new: Vec<u32> = (0..n)
        .map(|v| match rep[v] {
            REMOVED => REMOVED,
            r => new_index[r as usize],
        })
        .collect();
    for face in &mut faces {
        *face = face.map(|v| new_index[v as usize]);
    }
    Welded {
        mesh: TriMesh::new(vertices, faces),
        old_to_new,
        merged_vertices,
        removed_faces,
        removed_unreferenced,
        split_vertices: 0,
    }
}
