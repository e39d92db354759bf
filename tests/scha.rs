//! The spherical cap harmonics basis (`capmesh::harmonics::scha`): its degrees against the
//! cases known in closed form (the hemisphere's integers, the whole sphere's limit), an
//! independent check of the rim conditions through the hypergeometric form of `P_nu^-m`, and
//! orthonormality by quadrature over the cap.

use capmesh::harmonics::cap_legendre::{CapLegendre, Rim};
use capmesh::harmonics::{gauss_legendre, CapBasis, CapBoundary, SchaBasis};
use std::f64::consts::PI;

/// `(k, m)` pairs of the order-`n` basis with their index.
fn pairs(order: usize) -> Vec<(usize, isize)> {
    (0..=order).flat_map(|k| (-(k as isize)..=k as isize).map(move |m| (k, m))).collect()
}

#[test]
fn on_the_hemisphere_the_degrees_are_the_integers_of_each_parity() {
    const ORDER: usize = 12;
    let neumann = SchaBasis::new(0.0, ORDER, CapBoundary::Neumann).unwrap();
    let dirichlet = SchaBasis::new(0.0, ORDER, CapBoundary::Dirichlet).unwrap();
    let mixed = SchaBasis::new(0.0, ORDER, CapBoundary::Mixed).unwrap();
    let mut worst = 0.0f64;
    for (k, m) in pairs(ORDER) {
        let j = (k - m.unsigned_abs()) as f64;
        let am = m.unsigned_abs() as f64;
        // The j-th Neumann degree of order m is m + 2j (n - m even), the j-th Dirichlet one
        // m + 2j + 1 (n - m odd); the mixed set takes them alternately: degree k.
        let expected = [(neumann.degree(k, m).unwrap(), am + 2.0 * j), (dirichlet.degree(k, m).unwrap(), am + 2.0 * j + 1.0), (mixed.degree(k, m).unwrap(), k as f64)];
        for (found, want) in expected {
            worst = worst.max((found - want).abs());
            assert!((found - want).abs() < 1e-9, "(k, m) = ({k}, {m}): degree {found}, expected {want}");
        }
    }
    eprintln!("hemisphere: largest degree error {worst:.2e}");
}

#[test]
fn as_the_cap_grows_to_the_sphere_the_degrees_tend_to_the_integers() {
    const ORDER: usize = 8;
    let mut previous = f64::INFINITY;
    for z_star in [-0.9, -0.99, -0.999, -0.9999] {
        let basis = SchaBasis::new(z_star, ORDER, CapBoundary::Neumann).unwrap();
        let gap = pairs(ORDER).into_iter().map(|(k, m)| (basis.degree(k, m).unwrap() - k as f64).abs()).fold(0.0f64, f64::max);
        eprintln!("Neumann, Z* = {z_star}: largest |nu_k^m - k| = {gap:.3e}");
        // Each tenfold smaller hole shrinks the gap at least fivefold.
        assert!(gap < 0.2 * previous, "Z* = {z_star}: {gap} not below a fifth of {previous}");
        previous = gap;
    }
    assert!(previous < 5e-3, "{previous}");
    // Dirichlet, m >= 1: the j-th degree tends to m + j as well.
    let mut previous = f64::INFINITY;
    for z_star in [-0.9, -0.99, -0.999] {
        let basis = SchaBasis::new(z_star, ORDER, CapBoundary::Dirichlet).unwrap();
        let gap = pairs(ORDER).into_iter().filter(|&(_, m)| m != 0).map(|(k, m)| (basis.degree(k, m).unwrap() - k as f64).abs()).fold(0.0f64, f64::max);
        eprintln!("Dirichlet m >= 1, Z* = {z_star}: largest |nu_k^m - k| = {gap:.3e}");
        assert!(gap < 0.2 * previous, "Z* = {z_star}: {gap} not below a fifth of {previous}");
        previous = gap;
    }
    assert!(previous < 0.05, "{previous}");
}

#[test]
fn on_the_whole_sphere_the_neumann_basis_is_the_spherical_harmonics() {
    const ORDER: usize = 10;
    // Z* = -1 itself takes the integer-degree recurrence; the Rayleigh-Ritz functions of a cap
    // just short of the sphere must agree with it (the limit, computed the other way).
    let ah = CapBasis::new(-1.0, ORDER).unwrap();
    let sphere = SchaBasis::new(-1.0, ORDER, CapBoundary::Neumann).unwrap();
    let almost = SchaBasis::new(-1.0 + 1e-12, ORDER, CapBoundary::Neumann).unwrap();
    for (i, p) in [[0.0, 0.0, 1.0], [0.6, 0.0, 0.8], [0.36, -0.48, 0.8], [-0.5, 0.5, -0.5f64.sqrt()], [0.0, 0.6, -0.8]].into_iter().enumerate() {
        let b = ah.evaluate(p).unwrap();
        for (basis, tolerance) in [(&sphere, 1e-12), (&almost, 1e-6)] {
            let a = basis.evaluate(p).unwrap();
            for (j, (x, y)) in a.iter().zip(&b).enumerate() {
                assert!((x - y).abs() < tolerance * (1.0 + y.abs()), "Z* = {}, point {i}, function {j}: {x} vs {y}", basis.z_star());
            }
        }
    }
}

#[test]
fn on_the_whole_sphere_every_rim_condition_gives_the_spherical_harmonics() {
    // At Z* = -1 the rim is a point: no condition is left, the degrees are the integers and
    // the functions the real spherical harmonics, for Neumann, Dirichlet and mixed alike
    // (the basis of a closed surface, harmonics::scha::basis_cap).
    const ORDER: usize = 12;
    let ah = CapBasis::new(-1.0, ORDER).unwrap();
    for boundary in [CapBoundary::Neumann, CapBoundary::Dirichlet, CapBoundary::Mixed] {
        let basis = SchaBasis::new(-1.0, ORDER, boundary).unwrap();
        for (k, m) in pairs(ORDER) {
            assert_eq!(basis.degree(k, m), Some(k as f64), "{boundary:?} ({k}, {m})");
        }
        for p in [[0.0, 0.0, -1.0], [0.28, 0.96, 0.0], [-0.6, 0.0, -0.8]] {
            assert_eq!(basis.evaluate(p).unwrap(), ah.evaluate(p).unwrap(), "{boundary:?} at {p:?}");
        }
    }
    assert_eq!(capmesh::harmonics::scha::basis_cap(-0.99, true), -1.0);
    assert_eq!(capmesh::harmonics::scha::basis_cap(-0.99, false), -0.99);
}

/// `2F1(a, b; c; z)` by its series (|z| < 1), and the series of `d/dz`.
fn hypergeometric(a: f64, b: f64, c: f64, z: f64) -> f64 {
    let (mut term, mut sum) = (1.0, 1.0);
    for k in 0..100_000 {
        let kf = k as f64;
        term *= (a + kf) * (b + kf) / ((c + kf) * (kf + 1.0)) * z;
        sum += term;
        if term.abs() < 1e-17 * sum.abs() && k > 10 {
            break;
        }
    }
    sum
}

#[test]
fn the_degrees_are_the_roots_of_the_rim_condition_of_the_hypergeometric_legendre_function() {
    // P_nu^-m(cos theta) is proportional to sin(theta)^m 2F1(m - nu, m + nu + 1; 1 + m; z),
    // z = (1 - cos theta) / 2 (its series form after Euler's transformation): an independent
    // description of the regular solution. Dirichlet: F(z_c) = 0; Neumann:
    // m cos(theta_c) F + sin(theta_c)^2 / 2 dF/dz = 0. Each degree is refined by the secant
    // method on that condition and must agree with the Rayleigh-Ritz one.
    let mut worst = 0.0f64;
    for z_star in [0.9, 0.5, -0.3, -0.95] {
        let zc = 0.5 * (1.0 - z_star);
        let s2 = 1.0 - z_star * z_star;
        for m in 0..4usize {
            let mf = m as f64;
            for rim in [Rim::Neumann, Rim::Dirichlet] {
                let condition = |nu: f64| {
                    let (a, b, c) = (mf - nu, mf + nu + 1.0, 1.0 + mf);
                    let f = hypergeometric(a, b, c, zc);
                    match rim {
                        Rim::Dirichlet => f,
                        Rim::Neumann => mf * z_star * f + 0.5 * s2 * a * b / c * hypergeometric(a + 1.0, b + 1.0, c + 1.0, zc),
                    }
                };
                let family = CapLegendre::new(z_star, m, 5, rim).unwrap();
                for (j, &nu) in family.degrees().iter().enumerate() {
                    if rim == Rim::Neumann && m == 0 && j == 0 {
                        assert!(nu.abs() < 1e-7, "the constant has degree {nu}");
                        continue;
                    }
                    let (mut x0, mut x1) = (nu * (1.0 - 1e-6) - 1e-9, nu);
                    let (mut f0, mut f1) = (condition(x0), condition(x1));
                    for _ in 0..60 {
                        if f1 == f0 || (x1 - x0).abs() < 1e-15 * nu.abs().max(1.0) {
                            break;
                        }
                        let x2 = x1 - f1 * (x1 - x0) / (f1 - f0);
                        (x0, f0, x1) = (x1, f1, x2);
                        f1 = condition(x1);
                    }
                    let gap = (x1 - nu).abs();
                    worst = worst.max(gap);
                    assert!(gap < 1e-8 * nu.max(1.0), "Z* = {z_star}, m = {m}, {rim:?} j = {j}: Rayleigh-Ritz {nu}, series root {x1}");
                }
            }
        }
    }
    eprintln!("largest |nu_ritz - nu_series| = {worst:.2e}");
}

#[test]
fn the_neumann_and_dirichlet_sets_are_orthonormal_on_the_cap() {
    const ORDER: usize = 8;
    for z_star in [-0.6, 0.3, 0.85] {
        for boundary in [CapBoundary::Neumann, CapBoundary::Dirichlet] {
            let basis = SchaBasis::new(z_star, ORDER, boundary).unwrap();
            let p = basis.len();
            let mut gram = vec![0.0; p * p];
            // Gauss-Legendre in cos(theta) over [Z*, 1] times the trapezoid rule in phi (exact
            // for trigonometric polynomials of degree below 64).
            let half = 0.5 * (1.0 - z_star);
            let phis = 64;
            for (t, w) in gauss_legendre(90).unwrap() {
                let x = 1.0 - half * (1.0 - t);
                let theta = x.clamp(-1.0, 1.0).acos();
                for q in 0..phis {
                    let phi = 2.0 * PI * q as f64 / phis as f64;
                    let v = basis.evaluate_angles(theta, phi).unwrap();
                    let weight = w * half * 2.0 * PI / phis as f64;
                    for i in 0..p {
                        for j in 0..=i {
                            gram[i * p + j] += weight * v[i] * v[j];
                        }
                    }
                }
            }
            let mut worst = 0.0f64;
            for i in 0..p {
                for j in 0..=i {
                    let want = if i == j { 1.0 } else { 0.0 };
                    worst = worst.max((gram[i * p + j] - want).abs());
                }
            }
            eprintln!("Z* = {z_star}, {boundary:?}: largest |G - I| = {worst:.2e}");
            assert!(worst < 1e-9, "Z* = {z_star}, {boundary:?}: Gram matrix off the identity by {worst}");
        }
    }
}

#[test]
fn the_rim_conditions_hold() {
    const ORDER: usize = 7;
    for z_star in [-0.7f64, 0.2, 0.9] {
        let theta_c = z_star.acos();
        let neumann = SchaBasis::new(z_star, ORDER, CapBoundary::Neumann).unwrap();
        let dirichlet = SchaBasis::new(z_star, ORDER, CapBoundary::Dirichlet).unwrap();
        let h = 1e-5 * theta_c;
        for phi in [0.3, 2.0] {
            let at = dirichlet.evaluate_angles(theta_c, phi).unwrap();
            let inside = dirichlet.evaluate_angles(0.5 * theta_c, phi).unwrap();
            assert!(at.iter().all(|v| v.abs() < 1e-10), "Dirichlet values on the rim: {at:?}");
            assert!(inside.iter().any(|v| v.abs() > 0.1), "Dirichlet functions vanish inside too");
            let (a, b) = (neumann.evaluate_angles(theta_c, phi).unwrap(), neumann.evaluate_angles(theta_c - h, phi).unwrap());
            let (c, d) = (dirichlet.evaluate_angles(theta_c, phi).unwrap(), dirichlet.evaluate_angles(theta_c - h, phi).unwrap());
            for i in 0..a.len() {
                // One-sided difference: O(h) against the Dirichlet functions' O(1) slopes.
                let slope = (a[i] - b[i]) / h;
                let scale = ((c[i] - d[i]) / h).abs().max(1.0);
                assert!(slope.abs() < 1e-3 * scale, "Z* = {z_star}, function {i}: Neumann slope {slope} (Dirichlet {scale})");
            }
            assert!(a.iter().skip(1).any(|v| v.abs() > 0.1), "Neumann functions vanish on the rim");
        }
    }
}

#[test]
fn bad_requests_are_errors() {
    assert!(SchaBasis::new(1.0, 3, CapBoundary::Neumann).is_err());
    assert!(SchaBasis::new(f64::NAN, 3, CapBoundary::Neumann).is_err());
    assert!(SchaBasis::new(0.0, 1000, CapBoundary::Neumann).is_err());
    let basis = SchaBasis::new(0.5, 3, CapBoundary::Mixed).unwrap();
    let msg = basis.evaluate([0.0, 0.6, -0.8]).unwrap_err().to_string();
    assert!(msg.contains("Z*"), "{msg}");
    assert!(basis.evaluate([0.0, 0.0, 2.0]).unwrap_err().to_string().contains("norm"));
    assert_eq!(basis.degree(2, 3), None);
}
