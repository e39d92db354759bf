//! The local side of the area refinement ([`super::area_refine`]): each vertex's wedges
//! (its faces seen from it), the damped Gauss-Newton step of one vertex, and the colour
//! classes (vertices that share no face) a sweep steps in parallel, renumbered so that a
//! class is contiguous in memory.

use super::area_refine::VertexLift;
use crate::mesh::geometry::{cross, dot, signed_area_2d, sub, triangle_area};

/// The vertices renumbered class by class for the sweeps: the free vertices of each colour
/// class (see [`color_classes`]) in a contiguous range, in vertex order, then every other
/// vertex. A sweep visits one class after another, so its vertices' positions and wedges are
/// read in storage order rather than strided over the whole mesh: the hand's refinement
/// spent about a sixth of its time waiting for the first wedge of each vertex. The faces,
/// and each vertex's wedges, keep their order, so the arithmetic and the maps are the same.
pub(super) struct ClassOrder {
    /// `order[i]`: the vertex at class position `i`.
    pub(super) order: Vec<usize>,
    /// The ranges of class positions of the colour classes.
    pub(super) ranges: Vec<std::ops::Range<usize>>,
    /// The faces in class positions.
    pub(super) faces: Vec<[u32; 3]>,
    /// The wedges in class positions.
    pub(super) wedges: Wedges,
}

impl ClassOrder {
    pub(super) fn new(n: usize, faces: &[[u32; 3]], fixed: &[bool], ln_source: &[f64]) -> Self {
        let colors = color_classes(&Wedges::new(n, faces, ln_source), fixed);
        let mut ranges = Vec::with_capacity(colors.len());
        let mut order = Vec::with_capacity(n);
        for class in &colors {
            let start = order.len();
            order.extend_from_slice(class);
            ranges.push(start..order.len());
        }
        let mut position = vec![usize::MAX; n];
        for (i, &v) in order.iter().enumerate() {
            position[v] = i;
        }
        for (v, slot) in position.iter_mut().enumerate() {
            if *slot == usize::MAX {
                *slot = order.len();
                order.push(v);
            }
        }
        let faces: Vec<[u32; 3]> = faces.iter().map(|f| f.map(|v| position[v as usize] as u32)).collect();
        let wedges = Wedges::new(n, &faces, ln_source);
        Self { order, ranges, faces, wedges }
    }
}

/// One face seen from one of its corners `v`: the next two corners counter-clockwise (so
/// `(v, a, b)` has the face's orientation) and `ln` of the face's source area (NaN where it
/// is not positive). A vertex's step reads only its wedges and its neighbours' positions,
/// which is faster than per-vertex face lists that look up each face's corners and area.
#[derive(Debug, Clone, Copy)]
pub(super) struct Wedge {
    pub(super) a: u32,
    pub(super) b: u32,
    pub(super) ln_source: f64,
}

/// Every vertex's wedges, in one array (vertex `v`'s at `start[v]..start[v + 1]`).
pub(super) struct Wedges {
    pub(super) start: Vec<usize>,
    pub(super) wedges: Vec<Wedge>,
}

impl Wedges {
    pub(super) fn new(n: usize, faces: &[[u32; 3]], ln_source: &[f64]) -> Self {
        let mut start = vec![0usize; n + 1];
        for f in faces {
            for &v in f {
                start[v as usize + 1] += 1;
            }
        }
        for v in 0..n {
            start[v + 1] += start[v];
        }
        let mut next = start.clone();
        let mut wedges = vec![Wedge { a: 0, b: 0, ln_source: f64::NAN }; start[n]];
        for (f, &ln_source) in faces.iter().zip(ln_source) {
            for k in 0..3 {
                let v = f[k] as usize;
                wedges[next[v]] = Wedge { a: f[(k + 1) % 3], b: f[(k + 2) % 3], ln_source };
                next[v] += 1;
            }
        }
        Self { start, wedges }
    }

    pub(super) fn at(&self, v: usize) -> &[Wedge] {
        &self.wedges[self.start[v]..self.start[v + 1]]
    }
}

/// The data one vertex's Gauss-Newton step reads besides its wedges.
pub(super) struct LocalProblem<'a> {
    /// `ln(total image area) - ln(total source area)`.
    pub(super) offset: f64,
    /// +1 or -1: the orientation planar faces must keep.
    pub(super) orientation: f64,
    pub(super) lift: &'a VertexLift<'a>,
    /// The line search's first trial, in Gauss-Newton steps.
    pub(super) over_relaxation: f64,
}

/// A vertex's accepted step: its new planar and lifted positions, and the planar move
/// divided by its shortest planar edge.
pub(super) struct Step {
    pub(super) plane: [f64; 2],
    pub(super) lifted: [f64; 3],
    pub(super) relative_move: f64,
}

/// One face's residual `d_area` at a vertex and its gradient `d ln A / d l_v` with respect
/// to the vertex's lifted position.
#[derive(Debug, Clone, Copy)]
pub(super) struct Linearized {
    pub(super) residual: f64,
    pub(super) gradient: [f64; 3],
}

impl LocalProblem<'_> {
    /// The residuals `d_area` of the faces `local` around vertex `v` at its current position
    /// and their gradients into `out` (cleared first); the sum of squared residuals and the
    /// shortest planar edge at `v`. `None` when a face has lost the plane's orientation or
    /// has no area. The gradient of a triangle's area at a corner is half the unit normal
    /// crossed with the opposite edge, so `grad ln A = n x (b - a) / |n|^2` with `n` the
    /// corner's cross product: one cross product per face gives both.
    pub(super) fn linearize(&self, v: usize, local: &[Wedge], plane: &[[f64; 2]], lifted: &[[f64; 3]], out: &mut Vec<Linearized>) -> Option<(f64, f64)> {
        out.clear();
        let (p0, l0) = (plane[v], lifted[v]);
        let (mut energy, mut shortest2) = (0.0, f64::INFINITY);
        for w in local {
            let (pa, pb) = (plane[w.a as usize], plane[w.b as usize]);
            if self.orientation * signed_area_2d(p0, pa, pb) <= 0.0 {
                return None;
            }
            for q in [pa, pb] {
                shortest2 = f64::min(shortest2, (q[0] - p0[0]).powi(2) + (q[1] - p0[1]).powi(2));
            }
            let (a, b) = (lifted[w.a as usize], lifted[w.b as usize]);
            let n = cross(sub(a, l0), sub(b, l0));
            let nn = dot(n, n);
            let twice_area = nn.sqrt();
            if !(twice_area > 0.0 && w.ln_source.is_finite()) {
                return None;
            }
            let residual = (0.5 * twice_area).ln() - w.ln_source - self.offset;
            energy += residual * residual;
            out.push(Linearized { residual, gradient: cross(n, sub(b, a)).map(|x| x / nn) });
        }
        Some((energy, shortest2.sqrt()))
    }

    /// Whether the vertex placed at `p` (lifted `lp`) keeps every face of `local` oriented
    /// with positive area and brings the sum of squared residuals below `bound` (stopping at
    /// the first face that decides it).
    fn lowers(&self, p: [f64; 2], lp: [f64; 3], local: &[Wedge], plane: &[[f64; 2]], lifted: &[[f64; 3]], bound: f64) -> bool {
        let mut energy = 0.0;
        for w in local {
            let (a, b) = (w.a as usize, w.b as usize);
            if self.orientation * signed_area_2d(p, plane[a], plane[b]) <= 0.0 {
                return false;
            }
            let area = triangle_area(lp, lifted[a], lifted[b]);
            if !(area > 0.0) {
                return false;
            }
            let r = area.ln() - w.ln_source - self.offset;
            energy += r * r;
            if !(energy < bound) {
                return false;
            }
        }
        true
    }

    /// The lift's Jacobian `dl/dp` at `p` (lifted `lp`; vertex `v` moving) by forward
    /// differences of step `h`: one lift per column.
    pub(super) fn lift_jacobian(&self, v: usize, p: [f64; 2], lp: [f64; 3], h: f64) -> [[f64; 3]; 2] {
        [0, 1].map(|k| {
            let mut q = p;
            q[k] += h;
            let l = (self.lift)(v, q);
            [(l[0] - lp[0]) / h, (l[1] - lp[1]) / h, (l[2] - lp[2]) / h]
        })
    }

    /// A damped, possibly over-relaxed Gauss-Newton step of the free vertex `v` on
    /// `sum_{T at v} d_area(T)^2`, or `None` when no step lowers the sum. The residuals'
    /// Jacobian with respect to the planar position is `grad ln A . dl/dp`, `dl/dp` taken at
    /// the scale of the shortest incident edge.
    pub(super) fn step(&self, v: usize, local: &[Wedge], plane: &[[f64; 2]], lifted: &[[f64; 3]], scratch: &mut Vec<Linearized>) -> Option<Step> {
        if local.is_empty() {
            return None;
        }
        let (e0, shortest) = self.linearize(v, local, plane, lifted, scratch)?;
        let h = 1e-6 * shortest;
        if !(h > 0.0) {
            return None;
        }
        let p0 = plane[v];
        let dl = self.lift_jacobian(v, p0, lifted[v], h);
        // Gauss-Newton step: (J^T J + eps I) s = -J^T r.
        let (mut a, mut b, mut c, mut g0, mut g1) = (0.0, 0.0, 0.0, 0.0, 0.0);
        for f in scratch.iter() {
            let j = [dot(f.gradient, dl[0]), dot(f.gradient, dl[1])];
            a += j[0] * j[0];
            b += j[0] * j[1];
            c += j[1] * j[1];
            g0 += j[0] * f.residual;
            g1 += j[1] * f.residual;
        }
        let eps = 1e-9 * (a + c);
        let (a, c) = (a + eps, c + eps);
        let det = a * c - b * b;
        if !(det > 0.0) {
            return None;
        }
        let step = [-(c * g0 - b * g1) / det, -(a * g1 - b * g0) / det];
        let mut t = self.over_relaxation;
        for _ in 0..8 {
            let p = [p0[0] + t * step[0], p0[1] + t * step[1]];
            let lp = (self.lift)(v, p);
            if self.lowers(p, lp, local, plane, lifted, e0) {
                return Some(Step { plane: p, lifted: lp, relative_move: t * step[0].hypot(step[1]) / shortest });
            }
            t *= 0.5;
        }
        None
    }
}

/// The free vertices with incident faces, in classes of which no two share a face (greedy
/// colouring in vertex order; planar meshes need about 7 to 9 classes).
pub(super) fn color_classes(wedges: &Wedges, fixed: &[bool]) -> Vec<Vec<usize>> {
    let n = fixed.len();
    let mut color = vec![usize::MAX; n];
    let mut classes: Vec<Vec<usize>> = Vec::new();
    let mut taken: Vec<bool> = Vec::new();
    for v in 0..n {
        if fixed[v] || wedges.at(v).is_empty() {
            continue;
        }
        taken.clear();
        taken.resize(classes.len() + 1, false);
        for w in wedges.at(v) {
            for u in [w.a, w.b] {
                let c = color[u as usize];
                if c != usize::MAX {
                    taken[c] = true;
                }
            }
        }
        let c = taken.iter().position(|&x| !x).unwrap_or(classes.len());
        if c == classes.len() {
            classes.push(Vec::new());
        }
        color[v] = c;
        classes[c].push(v);
    }
    classes
}
