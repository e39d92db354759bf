//! Small vector helpers and per-face / per-vertex geometry (areas, angles).

/// `a - b`.
#[inline]
pub fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `a + b`.
#[inline]
pub fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// `s * a`.
#[inline]
pub fn scale(a: [f64; 3], s: f64) -> [f64; 3] {
    [a[0] * s, a[1] * s, a[2] * s]
}

/// Dot product.
#[inline]
pub fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Cross product.
#[inline]
pub fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Euclidean norm.
#[inline]
pub fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

/// Area of the triangle `abc`.
#[inline]
pub fn triangle_area(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> f64 {
    0.5 * norm(cross(sub(b, a), sub(c, a)))
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
    let corner = |p: [f64; 3], q: [f64; 3], r: [f64; 3]| {
        let u = sub(q, p);
        let v = sub(r, p);
        norm(cross(u, v)).atan2(dot(u, v))
    };
    [corner(a, b, c), corner(b, c, a), corner(c, a, b)]
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
