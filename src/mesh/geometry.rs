//! Small vector helpers and per-face / per-vertex geometry (areas, angles).
//!
//! The arithmetic is nalgebra's `Vector3` (issue 30). A mesh stores its points as
//! `[f64; 3]` (the layout of the readers, the writers and the C ABI's arrays), so these
//! helpers take and return `[f64; 3]` and convert by value, without allocating; the many
//! call sites that read a mesh's points stay as they are. Kernels with more algebra than a
//! sum or a product (the puncture's principal axis, the Jacobians of the distortion
//! measures and of the remesh's one-rings) use nalgebra's types directly. The helpers give
//! the same bits as the hand-written arithmetic they replaced (nalgebra's `dot`, `cross` and
//! `norm` on 3-vectors evaluate in the same order; tests/geometry_kernels.rs checks it), so
//! `param` and `remesh` write the same bytes (docs/dependencies.md).

use nalgebra::Vector3;

/// `a - b`.
#[inline]
pub fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    (Vector3::from(a) - Vector3::from(b)).into()
}

/// `a + b`.
#[inline]
pub fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    (Vector3::from(a) + Vector3::from(b)).into()
}

/// `s * a`.
#[inline]
pub fn scale(a: [f64; 3], s: f64) -> [f64; 3] {
    (Vector3::from(a) * s).into()
}

/// Dot product.
#[inline]
pub fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    Vector3::from(a).dot(&Vector3::from(b))
}

/// Cross product.
#[inline]
pub fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    Vector3::from(a).cross(&Vector3::from(b)).into()
}

/// Euclidean norm.
#[inline]
pub fn norm(a: [f64; 3]) -> f64 {
    Vector3::from(a).norm()
}

/// The edge of an equilateral triangle of area `area / faces`: the mean edge length of
/// `faces` well-shaped triangles covering `area`.
#[inline]
pub fn equilateral_edge(area: f64, faces: f64) -> f64 {
    (4.0 * area / (3f64.sqrt() * faces)).sqrt()
}

/// Area of the triangle `abc`.
#[inline]
pub fn triangle_area(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> f64 {
    let a = Vector3::from(a);
    0.5 * (Vector3::from(b) - a).cross(&(Vector3::from(c) - a)).norm()
}

/// The gradient of `ln` of the area of triangle `xab` with respect to its corner `x`:
/// `n x (b - a) / |n|^2` with `n = (a - x) x (b - x)` (infinite or NaN without area).
#[inline]
pub(crate) fn ln_triangle_area_gradient(x: [f64; 3], a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    let n = cross(sub(a, x), sub(b, x));
    let nn = dot(n, n);
    cross(n, sub(b, a)).map(|c| c / nn)
}

/// Signed area of the planar triangle `abc` (positive when counter-clockwise).
#[inline]
pub fn signed_area_2d(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
}

/// The three interior angles (radians) of triangle `abc`, at `a`, `b`, `c`.
///
/// Uses `atan2(|u x v|, u . v)`, accurate for needles and caps. A corner where an incident
/// edge has zero length gets angle 0.
#[inline]
pub fn triangle_angles(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> [f64; 3] {
    let corner = |p: &Vector3<f64>, q: &Vector3<f64>, r: &Vector3<f64>| {
        let (u, v) = (q - p, r - p);
        u.cross(&v).norm().atan2(u.dot(&v))
    };
    let [a, b, c] = [a, b, c].map(Vector3::from);
    [corner(&a, &b, &c), corner(&b, &c, &a), corner(&c, &a, &b)]
}

/// Area of every face.
pub fn face_areas(vertices: &[[f64; 3]], faces: &[[u32; 3]]) -> Vec<f64> {
    faces
        .iter()
        .map(|f| {
            triangle_area(
                vertices[f[0] as usize],
                vertices[f[1] as usize],
                vertices[f[2] as usize],
            )
        })
        .collect()
}

/// The sum of the corner angles ([`triangle_angles`]) of each vertex's faces: `2 pi` minus it
/// is an interior vertex's angle defect (its Gaussian curvature times its area).
pub fn angle_sums(vertices: &[[f64; 3]], faces: &[[u32; 3]]) -> Vec<f64> {
    let mut sum = vec![0.0; vertices.len()];
    for f in faces {
        let ang = triangle_angles(vertices[f[0] as usize], vertices[f[1] as usize], vertices[f[2] as usize]);
        for k in 0..3 {
            sum[f[k] as usize] += ang[k];
        }
    }
    sum
}

/// Vertex areas: one third of the area of the incident faces (the paper's `A_v`, Sec. 3.1.2).
pub fn vertex_areas(vertices: &[[f64; 3]], faces: &[[u32; 3]]) -> Vec<f64> {
    let mut out = vec![0.0; vertices.len()];
    for (f, a) in faces.iter().zip(face_areas(vertices, faces)) {
        for &v in f {
            out[v as usize] += a / 3.0;
        }
    }
    out
}

/// Faces of a planar map with non-positive signed area (folded or degenerate).
pub fn folded_faces(uv: &[[f64; 2]], faces: &[[u32; 3]]) -> Vec<usize> {
    faces
        .iter()
        .enumerate()
        .filter(|(_, f)| signed_area_2d(uv[f[0] as usize], uv[f[1] as usize], uv[f[2] as usize]) <= 0.0)
        .map(|(i, _)| i)
        .collect()
}

/// Lift planar points to `z = 0`.
pub fn lift(points: &[[f64; 2]]) -> Vec<[f64; 3]> {
    points.iter().map(|p| [p[0], p[1], 0.0]).collect()
}
