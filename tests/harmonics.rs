//! Adaptive harmonics (paper Sec. "Adaptive Harmonics (AH)"): Legendre functions against closed
//! forms, orthonormality of the basis over the cap by quadrature, exact recovery of known
//! combinations, falling reconstruction error on real meshes, and the order-1 aspect ratio.

mod common;

use common::data;

use std::f64::consts::PI;

use capmesh::harmonics::legendre::triangle_index;
use capmesh::harmonics::{
    aspect_ratio, associated_legendre, basis_degree, basis_index, basis_len, fit, fit_all_orders, gauss_legendre,
    normalized_legendre, order_one_ellipsoid, CapBasis, HarmonicFit, HarmonicsError,
};
use capmesh::mesh::shapes::{spherical_cap, spherical_cap_sectors, uv_sphere};

/// Deterministic pseudo-random numbers in [-1, 1] (xorshift64*).
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let x = self.0.wrapping_mul(0x2545_F491_4F6C_DD1D);
        (x >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }
}

fn cap_points(z0: f64, rings: usize) -> Vec<[f64; 3]> {
    spherical_cap(z0, rings, spherical_cap_sectors(z0, rings)).vertices
}

// ---------------------------------------------------------------- Legendre functions

#[test]
fn legendre_matches_closed_forms() {
    for &x in &[-1.0, -0.93, -0.5, 0.0, 0.21, 0.77, 1.0] {
        let s = (1.0f64 - x * x).sqrt();
        let expected = [
            (0, 0, 1.0),
            (1, 0, x),
            (1, 1, -s),
            (2, 0, 0.5 * (3.0 * x * x - 1.0)),
            (2, 1, -3.0 * x * s),
            (2, 2, 3.0 * s * s),
            (3, 0, 0.5 * (5.0 * x * x * x - 3.0 * x)),
            (3, 1, -1.5 * (5.0 * x * x - 1.0) * s),
            (3, 2, 15.0 * x * s * s),
            (3, 3, -15.0 * s * s * s),
            (4, 0, (35.0 * x.powi(4) - 30.0 * x * x + 3.0) / 8.0),
        ];
        for (n, m, want) in expected {
            let got = associated_legendre(n, m, x).unwrap();
            assert!(
                (got - want).abs() < 1e-13 * want.abs().max(1.0),
                "P_{n}^{m}({x}) = {got}, want {want}"
            );
        }
    }
    // P_60^60(0) = (-1)^60 (119)!! = product of odd numbers up to 119 (about 1.3e97).
    let got = associated_legendre(60, 60, 0.0).unwrap();
    let want: f64 = (1..=60).map(|k| (2 * k - 1) as f64).product();
    assert!((got / want - 1.0).abs() < 1e-12, "P_60^60(0) = {got:e}, want {want:e}");
    assert!(matches!(
        associated_legendre(2, 3, 0.0),
        Err(HarmonicsError::InvalidDegree { .. })
    ));
    assert!(matches!(
        normalized_legendre(1.5, 3),
        Err(HarmonicsError::ArgumentOutOfRange { .. })
    ));
    assert!(matches!(
        normalized_legendre(f64::NAN, 3),
        Err(HarmonicsError::ArgumentOutOfRange { .. })
    ));
    assert!(matches!(
        normalized_legendre(0.1, 100_000),
        Err(HarmonicsError::OrderTooLarge { .. })
    ));
    // Unnormalized values overflow f64 long before the normalized ones do.
    assert!(matches!(
        associated_legendre(200, 200, 0.0),
        Err(HarmonicsError::Overflow { .. })
    ));
}

#[test]
fn normalized_legendre_is_orthonormal_up_to_order_60() {
    let n_max = 60;
    let rule = gauss_legendre(128).unwrap();
    let len = triangle_index(n_max, n_max) + 1;
    let mut gram = vec![0.0; len * (n_max + 1)];
    // gram[idx(n, m) * (n_max + 1) + k] = integral Pbar_n^m Pbar_k^m (for k >= m).
    for &(x, w) in &rule {
        let p = normalized_legendre(x, n_max).unwrap();
        assert!(p.iter().all(|v| v.is_finite()));
        for n in 0..=n_max {
            for m in 0..=n {
                for k in m..=n_max {
                    gram[triangle_index(n, m) * (n_max + 1) + k] +=
                        w * p[triangle_index(n, m)] * p[triangle_index(k, m)];
                }
            }
        }
    }
    let mut worst: f64 = 0.0;
    for n in 0..=n_max {
        for m in 0..=n {
            for k in m..=n_max {
                let want = if k == n { 1.0 } else { 0.0 };
                worst = worst.max((gram[triangle_index(n, m) * (n_max + 1) + k] - want).abs());
            }
        }
    }
    eprintln!("normalized Legendre up to N = 60: worst orthonormality error {worst:.2e}");
    assert!(worst < 1e-12, "worst orthonormality error {worst:e}");
}

#[test]
fn gauss_legendre_integrates_polynomials() {
    let rule = gauss_legendre(64).unwrap();
    assert_eq!(rule.len(), 64);
    let total: f64 = rule.iter().map(|&(_, w)| w).sum();
    assert!((total - 2.0).abs() < 1e-13);
    let x126: f64 = rule.iter().map(|&(x, w)| w * x.powi(126)).sum();
    assert!((x126 - 2.0 / 127.0).abs() < 1e-14, "{x126}");
    assert!(gauss_legendre(0).unwrap().is_empty());
}

// ---------------------------------------------------------------- the basis

#[test]
fn basis_indexing_round_trips() {
    for index in 0..basis_len(30) {
        let (n, m) = basis_degree(index);
        assert_eq!(basis_index(n, m), Some(index));
    }
    assert_eq!(basis_index(1, -1), Some(1));
    assert_eq!(basis_index(2, 3), None);
    assert_eq!(basis_len(3), 16);
    // Extreme arguments saturate instead of overflowing.
    assert_eq!(basis_index(usize::MAX, 0), None);
    let (n, m) = basis_degree(usize::MAX);
    assert!(m.unsigned_abs() <= n);
    assert_eq!(basis_len(usize::MAX), usize::MAX);
    assert_eq!(triangle_index(4, 2), 12);
    assert!(matches!(
        gauss_legendre(1_000_000),
        Err(HarmonicsError::OrderTooLarge { .. })
    ));
}

#[test]
fn basis_matches_closed_forms() {
    // Z* = -1: the usual real spherical harmonics.
    let sphere = CapBasis::new(-1.0, 2).unwrap();
    assert_eq!((sphere.q1(), sphere.q2()), (1.0, 0.0));
    let p = [0.48, -0.6, 0.64];
    let a = sphere.evaluate(p).unwrap();
    let c1 = (3.0 / (4.0 * PI)).sqrt();
    let want = [
        (1.0 / (4.0 * PI)).sqrt(),
        c1 * p[1],
        c1 * p[2],
        c1 * p[0],
        0.5 * (15.0 / PI).sqrt() * p[0] * p[1],
        0.5 * (15.0 / PI).sqrt() * p[1] * p[2],
        0.25 * (5.0 / PI).sqrt() * (3.0 * p[2] * p[2] - 1.0),
        0.5 * (15.0 / PI).sqrt() * p[0] * p[2],
        0.25 * (15.0 / PI).sqrt() * (p[0] * p[0] - p[1] * p[1]),
    ];
    for (i, (&got, &w)) in a.iter().zip(&want).enumerate() {
        assert!((got - w).abs() < 1e-14, "Z* = -1, function {i}: {got} vs {w}");
    }
    // A cap: A_1^0 = sqrt(3 q1 / 4 pi) t, A_1^1 = sqrt(3 q1 / 4 pi) sqrt(1 - t^2) cos(phi).
    let z_star = 0.3;
    let cap = CapBasis::new(z_star, 1).unwrap();
    let (q1, q2) = (cap.q1(), cap.q2());
    assert!((q1 * z_star + q2 + 1.0).abs() < 1e-15 && (q1 + q2 - 1.0).abs() < 1e-15);
    let (theta, phi) = (0.7f64, 2.2f64);
    let t = q1 * theta.cos() + q2;
    let k = (3.0 * q1 / (4.0 * PI)).sqrt();
    let want = [
        (q1 / (4.0 * PI)).sqrt(),
        k * (1.0 - t * t).sqrt() * phi.sin(),
        k * t,
        k * (1.0 - t * t).sqrt() * phi.cos(),
    ];
    let by_angles = cap.evaluate_angles(theta, phi).unwrap();
    let by_point = cap
        .evaluate([theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos()])
        .unwrap();
    for i in 0..4 {
        assert!(
            (by_angles[i] - want[i]).abs() < 1e-13,
            "{i}: {} vs {}",
            by_angles[i],
            want[i]
        );
        assert!(
            (by_point[i] - want[i]).abs() < 1e-13,
            "{i}: {} vs {}",
            by_point[i],
            want[i]
        );
    }
}

#[test]
fn representation_is_constant_on_the_boundary_circle() {
    // At Z = Z*, t = -1 and every P_n^m with m > 0 vanishes: only the zonal functions survive,
    // so any AH representation takes one value on the whole boundary circle (as for the
    // hemispherical harmonics the paper extends). Open surfaces lose their boundary shape.
    for &z_star in &[0.5, 0.0, -0.8] {
        let basis = CapBasis::new(z_star, 8).unwrap();
        let r = (1.0f64 - z_star * z_star).sqrt();
        let at = |phi: f64| basis.evaluate([r * phi.cos(), r * phi.sin(), z_star]).unwrap();
        let (a, b) = (at(0.3), at(2.9));
        for (i, (x, y)) in a.iter().zip(&b).enumerate() {
            let (_, m) = basis_degree(i);
            if m != 0 {
                assert!(x.abs() < 1e-6 && y.abs() < 1e-6, "Z* = {z_star}, function {i}: {x} {y}");
            } else {
                assert!((x - y).abs() < 1e-12);
            }
        }
    }
}

/// Gram matrix of the basis over the cap: Gauss-Legendre in cos(theta) on [Z*, 1] times the
/// uniform rule in phi, i.e. integral f g d(cos theta) d(phi) = integral f g dA.
fn cap_gram(z_star: f64, order: usize, nodes: usize, n_phi: usize) -> Vec<Vec<f64>> {
    let basis = CapBasis::new(z_star, order).unwrap();
    let len = basis.len();
    let mut gram = vec![vec![0.0; len]; len];
    let half = 0.5 * (1.0 - z_star);
    for (u, w) in gauss_legendre(nodes).unwrap() {
        let x = half * u + 0.5 * (1.0 + z_star);
        let r = ((1.0 - x) * (1.0 + x)).sqrt();
        for j in 0..n_phi {
            let phi = -PI + 2.0 * PI * j as f64 / n_phi as f64;
            let weight = w * half * 2.0 * PI / n_phi as f64;
            let a = basis.evaluate([r * phi.cos(), r * phi.sin(), x]).unwrap();
            for (i, row) in gram.iter_mut().enumerate() {
                for (k, g) in row.iter_mut().enumerate() {
                    *g += weight * a[i] * a[k];
                }
            }
        }
    }
    gram
}

#[test]
fn basis_is_orthonormal_over_the_cap() {
    for &z_star in &[0.6, 0.0, -0.7, -1.0, 0.95] {
        let gram = cap_gram(z_star, 6, 64, 128);
        let mut worst: f64 = 0.0;
        for (i, row) in gram.iter().enumerate() {
            for (k, &g) in row.iter().enumerate() {
                worst = worst.max((g - if i == k { 1.0 } else { 0.0 }).abs());
            }
        }
        eprintln!("Z* = {z_star}: 49 x 49 Gram matrix, worst |G - I| = {worst:.2e}");
        assert!(worst < 1e-10, "Z* = {z_star}: worst |G - I| = {worst:e}");
    }
}

// ---------------------------------------------------------------- fitting

fn combination(basis: &CapBasis, points: &[[f64; 3]], coefficients: &[[f64; 3]]) -> Vec<[f64; 3]> {
    points
        .iter()
        .map(|&p| {
            let a = basis.evaluate(p).unwrap();
            let mut y = [0.0; 3];
            for (v, c) in a.iter().zip(coefficients) {
                for d in 0..3 {
                    y[d] += v * c[d];
                }
            }
            y
        })
        .collect()
}

#[test]
fn fit_recovers_known_coefficients() {
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    for &z_star in &[0.6, 0.0, -0.7] {
        let points = cap_points(z_star, 30);
        let truth: Vec<[f64; 3]> = (0..16).map(|_| [rng.next(), rng.next(), rng.next()]).collect();
        let values = combination(&CapBasis::new(z_star, 3).unwrap(), &points, &truth);
        for order in [3, 5] {
            let f = fit(&points, &values, z_star, order).unwrap();
            assert_eq!(f.coefficients.len(), basis_len(order));
            let mut worst: f64 = 0.0;
            for (j, c) in f.coefficients.iter().enumerate() {
                let want = truth.get(j).copied().unwrap_or([0.0; 3]);
                for d in 0..3 {
                    worst = worst.max((c[d] - want[d]).abs());
                }
            }
            eprintln!(
                "Z* = {z_star}, {} points, order {order}: worst coefficient error {worst:.2e}",
                points.len()
            );
            assert!(
                worst < 1e-8,
                "Z* = {z_star}, order {order}: worst coefficient error {worst:e}"
            );
            // The reconstruction reproduces the values.
            let y = f.reconstruct(&points, order).unwrap();
            let err = y
                .iter()
                .zip(&values)
                .map(|(a, b)| (0..3).map(|d| (a[d] - b[d]).abs()).fold(0.0, f64::max))
                .fold(0.0, f64::max);
            assert!(err < 1e-9, "reconstruction error {err:e}");
        }
    }
}

#[test]
fn nested_fits_equal_separate_fits() {
    // Values outside the span of the basis, so every order's fit is a genuine compromise.
    let z_star = -0.4;
    let points = cap_points(z_star, 25);
    let values: Vec<[f64; 3]> = points
        .iter()
        .map(|p| [(2.0 * p[0]).exp(), (3.0 * p[1] * p[2]).sin(), 1.0 / (2.0 + p[0] + p[2])])
        .collect();
    let all = fit_all_orders(&points, &values, z_star, 6).unwrap();
    assert_eq!(all.len(), 7);
    for order in [0, 2, 4, 6] {
        let separate = fit(&points, &values, z_star, order).unwrap();
        assert_eq!(all[order].order, order);
        for (a, b) in all[order].coefficients.iter().zip(&separate.coefficients) {
            for d in 0..3 {
                assert!((a[d] - b[d]).abs() < 1e-10, "order {order}: {a:?} vs {b:?}");
            }
        }
    }
    // Truncating the order-6 fit is not the order-2 fit (the basis is not orthogonal on points).
    let truncated = &all[6].coefficients[..9];
    let differs = truncated
        .iter()
        .zip(&all[2].coefficients)
        .any(|(a, b)| (0..3).any(|d| (a[d] - b[d]).abs() > 1e-6));
    assert!(differs);
    // errors_by_order agrees with a separate fit and reconstruction at one order.
    let errors = all[6].errors_by_order(&points, &values).unwrap();
    assert_eq!(errors.len(), 7);
    let y = fit(&points, &values, z_star, 3)
        .unwrap()
        .reconstruct(&points, 3)
        .unwrap();
    let mean = y
        .iter()
        .zip(&values)
        .map(|(a, b)| ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt())
        .sum::<f64>()
        / points.len() as f64;
    assert!(
        (errors[3].mean_distance - mean).abs() < 1e-12,
        "{} vs {mean}",
        errors[3].mean_distance
    );
    // Serde round trip.
    let json = serde_json::to_string(&all[4]).unwrap();
    let back: HarmonicFit = serde_json::from_str(&json).unwrap();
    assert_eq!((back.order, back.z_star, back.coefficients.len()), (4, z_star, 25));
    for (a, b) in back.coefficients.iter().zip(&all[4].coefficients) {
        for d in 0..3 {
            assert!((a[d] - b[d]).abs() <= 1e-15 * b[d].abs(), "{a:?} vs {b:?}");
        }
    }
}

#[test]
fn bad_inputs_are_errors() {
    let z_star = 0.2;
    let points = cap_points(z_star, 10);
    let values = points.clone();
    let err = |r: Result<HarmonicFit, HarmonicsError>| r.unwrap_err();
    assert!(matches!(
        err(fit(&points, &values, 1.0, 2)),
        HarmonicsError::InvalidZStar { .. }
    ));
    assert!(matches!(
        err(fit(&points, &values, f64::NAN, 2)),
        HarmonicsError::InvalidZStar { .. }
    ));
    assert!(matches!(
        err(fit(&points, &values, -1.5, 2)),
        HarmonicsError::InvalidZStar { .. }
    ));
    assert!(matches!(
        err(fit(&points, &values, z_star, 10_000)),
        HarmonicsError::OrderTooLarge { .. }
    ));
    assert!(matches!(
        err(fit(&points, &values[1..], z_star, 2)),
        HarmonicsError::LengthMismatch { .. }
    ));
    assert!(matches!(
        err(fit(&points[..8], &values[..8], z_star, 2)),
        HarmonicsError::TooFewPoints { .. }
    ));
    assert!(matches!(
        err(fit(&[], &[], z_star, 0)),
        HarmonicsError::TooFewPoints { .. }
    ));
    let mut bad = values.clone();
    bad[5][1] = f64::NAN;
    assert!(matches!(
        err(fit(&points, &bad, z_star, 2)),
        HarmonicsError::NonFinite { index: 5, .. }
    ));
    let mut bad = points.clone();
    bad[7][0] = f64::INFINITY;
    assert!(matches!(
        err(fit(&bad, &values, z_star, 2)),
        HarmonicsError::NonFinite { index: 7, .. }
    ));
    let mut bad = points.clone();
    bad[3] = [2.0 * bad[3][0], 2.0 * bad[3][1], 2.0 * bad[3][2]];
    assert!(matches!(
        err(fit(&bad, &values, z_star, 2)),
        HarmonicsError::NotOnUnitSphere { index: 3, .. }
    ));
    let mut bad = points.clone();
    bad[4] = [0.0, 0.0, 0.0];
    assert!(matches!(
        err(fit(&bad, &values, z_star, 2)),
        HarmonicsError::NotOnUnitSphere { index: 4, .. }
    ));
    let mut bad = points.clone();
    bad[9] = [0.6, 0.8, 0.0];
    assert!(matches!(
        err(fit(&bad, &values, z_star, 2)),
        HarmonicsError::OutsideCap { index: 9, .. }
    ));
    // All points on one circle: A_0^0 and A_1^0 are both constant there.
    let ring: Vec<[f64; 3]> = (0..50)
        .map(|j| {
            let phi = 2.0 * PI * j as f64 / 50.0;
            [0.8 * phi.cos(), 0.8 * phi.sin(), 0.6]
        })
        .collect();
    assert!(matches!(
        err(fit(&ring, &ring, z_star, 1)),
        HarmonicsError::RankDeficient { column: 2, .. }
    ));
    // A fit whose coefficients do not match its order.
    let mut f = fit(&points, &values, z_star, 2).unwrap();
    f.coefficients.pop();
    assert!(matches!(
        f.reconstruct(&points, 2),
        Err(HarmonicsError::InvalidFit { .. })
    ));
    let f = fit(&points, &values, z_star, 2).unwrap();
    assert!(matches!(
        f.errors_by_order(&points, &values[1..]),
        Err(HarmonicsError::LengthMismatch { .. })
    ));
    assert!(matches!(
        aspect_ratio(&points, &values, 2.0),
        Err(HarmonicsError::InvalidZStar { .. })
    ));
    // A flat surface has an infinite aspect ratio.
    let flat: Vec<[f64; 3]> = points.iter().map(|p| [p[0], p[1], 0.0]).collect();
    assert!(matches!(
        aspect_ratio(&points, &flat, z_star),
        Err(HarmonicsError::DegenerateShape { .. })
    ));
}

// ---------------------------------------------------------------- real meshes

fn reconstruction_on(name: &str, bound_at_15: f64) {
    let mesh = capmesh::io::read_mesh(&data(name)).unwrap_or_else(|e| panic!("{e}"));
    let map = capmesh::param::parameterize(
        &mesh,
        &capmesh::param::ParamOptions::default(),
        &capmesh::progress::NoProgress,
    )
    .unwrap_or_else(|e| panic!("{name}: {e}"));
    let z_star = map.report.z_star.expect("the adaptive domain has a Z*");
    let f = fit(&map.cap, &mesh.vertices, z_star, 15).unwrap_or_else(|e| panic!("{name}: {e}"));
    let errors = f.errors_by_order(&map.cap, &mesh.vertices).unwrap();
    eprintln!("{name}: {} vertices, Z* = {z_star:.4}", mesh.vertices.len());
    for e in &errors {
        eprintln!(
            "  N = {:2}: mean {:.5} max {:.5} (relative to the bounding-box diagonal)",
            e.order, e.mean_relative, e.max_relative
        );
    }
    let picked: Vec<f64> = [1, 5, 10, 15].iter().map(|&n| errors[n].mean_relative).collect();
    assert!(
        picked.windows(2).all(|w| w[1] < w[0]),
        "{name}: not decreasing: {picked:?}"
    );
    assert!(
        picked[3] < bound_at_15,
        "{name}: mean relative error at N = 15 is {}",
        picked[3]
    );
    // The order-15 row is the fit returned by `fit`.
    let y = f.reconstruct(&map.cap, 15).unwrap();
    let mean = y
        .iter()
        .zip(&mesh.vertices)
        .map(|(a, b)| ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt())
        .sum::<f64>()
        / y.len() as f64;
    assert!(
        (mean - errors[15].mean_distance).abs() <= 1e-9 * mean.max(1.0),
        "{mean} vs {}",
        errors[15].mean_distance
    );
    let ratio = aspect_ratio(&map.cap, &mesh.vertices, z_star).unwrap();
    let ellipsoid = order_one_ellipsoid(&fit(&map.cap, &mesh.vertices, z_star, 1).unwrap()).unwrap();
    // The singular values (nalgebra's 3x3 SVD) equal those of faer's dense SVD, which computed
    // them before, to 1e-12 relative on this real mesh.
    for (what, matrix, values) in [
        ("aspect ratio", ratio.linear_map, ratio.singular_values),
        ("order-1 ellipsoid", ellipsoid.axes, ellipsoid.semi_axes),
    ] {
        let mut reference = faer::Mat::from_fn(3, 3, |i, j| matrix[i][j]).singular_values().unwrap();
        reference.sort_by(|x, y| y.total_cmp(x));
        for (s, r) in values.iter().zip(&reference) {
            assert!((s - r).abs() <= 1e-12 * reference[0], "{name}: {what}: {values:?} vs faer's {reference:?}");
        }
    }
    eprintln!(
        "  order-1 aspect ratio {:.4} (singular values {:?}); exact order-1 ellipsoid semi-axes {:?}",
        ratio.ratio, ratio.singular_values, ellipsoid.semi_axes
    );
}

#[test]
fn face_reconstruction_error_falls_with_order() {
    reconstruction_on("open_face_choi.obj.gz", 0.01);
}

#[test]
fn brain12k_reconstruction_error_falls_with_order() {
    reconstruction_on("closed_brain12k_choi.obj.gz", 0.015);
}

// ---------------------------------------------------------------- shape analysis

#[test]
fn ellipsoid_aspect_ratio_on_the_whole_sphere() {
    let points = uv_sphere(40, 80).vertices;
    // A rotated and shifted ellipsoid with semi-axes 3, 2, 1.
    let (a, b) = (0.4f64, 1.1f64);
    let rz = [[a.cos(), -a.sin(), 0.0], [a.sin(), a.cos(), 0.0], [0.0, 0.0, 1.0]];
    let rx = [[1.0, 0.0, 0.0], [0.0, b.cos(), -b.sin()], [0.0, b.sin(), b.cos()]];
    let values: Vec<[f64; 3]> = points
        .iter()
        .map(|p| {
            let e = [3.0 * p[0], 2.0 * p[1], p[2]];
            let u: [f64; 3] = std::array::from_fn(|i| (0..3).map(|j| rx[i][j] * e[j]).sum());
            let v: [f64; 3] = std::array::from_fn(|i| (0..3).map(|j| rz[i][j] * u[j]).sum::<f64>());
            [v[0] + 5.0, v[1] - 2.0, v[2] + 0.5]
        })
        .collect();
    let r = aspect_ratio(&points, &values, -1.0).unwrap();
    eprintln!(
        "whole sphere: ratio {} singular values {:?} translation {:?}",
        r.ratio, r.singular_values, r.translation
    );
    assert!((r.ratio - 3.0).abs() < 1e-6, "ratio {}", r.ratio);
    for (s, want) in r.singular_values.iter().zip([3.0, 2.0, 1.0]) {
        assert!((s - want).abs() < 1e-9, "{:?}", r.singular_values);
    }
    for (t, want) in r.translation.iter().zip([5.0, -2.0, 0.5]) {
        assert!((t - want).abs() < 1e-9, "{:?}", r.translation);
    }
    let e = order_one_ellipsoid(&fit(&points, &values, -1.0, 1).unwrap()).unwrap();
    assert!((e.aspect_ratio() - 3.0).abs() < 1e-9, "{:?}", e.semi_axes);
    for (c, want) in e.center.iter().zip([5.0, -2.0, 0.5]) {
        assert!((c - want).abs() < 1e-9, "{:?}", e.center);
    }
}

#[test]
fn ellipsoid_aspect_ratio_on_caps() {
    for &z_star in &[0.0, 0.6, -0.7] {
        let points = cap_points(z_star, 40);
        let values: Vec<[f64; 3]> = points.iter().map(|p| [3.0 * p[0], 2.0 * p[1], p[2]]).collect();
        let r = aspect_ratio(&points, &values, z_star).unwrap();
        let [s1, s2, s3] = r.singular_values;
        eprintln!(
            "Z* = {z_star}: ratio {:.6}, singular values {:?}",
            r.ratio, r.singular_values
        );
        // X and Y are shrunk by the same factor (Cauchy-Schwarz: at most 1), Z is exact.
        assert!((s1 / s2 - 1.5).abs() < 1e-9, "{:?}", r.singular_values);
        assert!((s3 - 1.0).abs() < 1e-9, "{:?}", r.singular_values);
        assert!(r.ratio <= 3.0 + 1e-9 && r.ratio > 2.0, "ratio {}", r.ratio);
        // The order-1 representation is exactly the ellipsoid centre + axes x~ on the stretched
        // sphere x~ = (s cos phi, s sin phi, t).
        let f = fit(&points, &values, z_star, 1).unwrap();
        let e = order_one_ellipsoid(&f).unwrap();
        let y = f.reconstruct(&points, 1).unwrap();
        let basis = CapBasis::new(z_star, 1).unwrap();
        for (i, (&p, yi)) in points.iter().zip(&y).enumerate() {
            let c = basis.coordinates(i, p).unwrap();
            let x = [c.s * c.cos_phi, c.s * c.sin_phi, c.t];
            for d in 0..3 {
                let want = e.center[d] + (0..3).map(|j| e.axes[d][j] * x[j]).sum::<f64>();
                assert!((yi[d] - want).abs() < 1e-12, "point {i}: {yi:?}");
            }
        }
    }
}

