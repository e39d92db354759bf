//! Jacobi-preconditioned conjugate gradients (Hestenes and Stiefel 1952; Saad, *Iterative
//! Methods for Sparse Linear Systems*, Alg. 9.1) for a symmetric positive definite system
//! with two right-hand sides, the two planar coordinates, iterated together with step
//! lengths of their own.
//!
//! Used where a system is solved once per matrix and a good first guess is at hand, so that
//! a sparse Cholesky factorization (ordering, symbolic and numeric) costs more than a few
//! dozen matrix products: the smoothing candidates of [`crate::refine::smoothing`].

/// How a solve ended.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CgOutcome {
    /// Iterations made.
    pub iterations: usize,
    /// Whether both residuals fell to the tolerance (relative to their right-hand sides).
    pub converged: bool,
}

/// Solve `A x = b` for both columns of `x` (`[f64; 2]` per unknown) from the first guess in
/// `x`, where `apply(x, y)` writes `y = A x` and `diagonal` is `A`'s diagonal (all positive).
/// Stops when `|b - A x| <= tolerance |b|` for both columns, after `max_iterations`, or when
/// a curvature `p . A p` is not positive (`A` is not positive definite; `converged` false).
pub fn jacobi_cg2(
    apply: impl Fn(&[[f64; 2]], &mut [[f64; 2]]),
    diagonal: &[f64],
    b: &[[f64; 2]],
    x: &mut [[f64; 2]],
    tolerance: f64,
    max_iterations: usize,
) -> CgOutcome {
    cg2(apply, diagonal, b, x, tolerance, max_iterations, false)
}

/// [`jacobi_cg2`] for a caller with another way to solve the system: it also gives up (not
/// converged) as soon as the residual's decrease over the last 25 (`STAGNATION_WINDOW`)
/// iterations, kept up, would not reach the tolerance within `max_iterations`. On a
/// marching-cubes surface of 124k vertices the smoothing systems' residuals stalled between
/// 1e-8 and 1e-9 of the right-hand side after 50-100 iterations and all 300 were made for
/// nothing (docs/method.md section 8).
pub fn jacobi_cg2_or_give_up(
    apply: impl Fn(&[[f64; 2]], &mut [[f64; 2]]),
    diagonal: &[f64],
    b: &[[f64; 2]],
    x: &mut [[f64; 2]],
    tolerance: f64,
    max_iterations: usize,
) -> CgOutcome {
    cg2(apply, diagonal, b, x, tolerance, max_iterations, true)
}

/// Iterations over which [`jacobi_cg2_or_give_up`] measures the residual's decrease; it
/// judges from twice this many iterations on.
pub const STAGNATION_WINDOW: usize = 25;

fn cg2(
    apply: impl Fn(&[[f64; 2]], &mut [[f64; 2]]),
    diagonal: &[f64],
    b: &[[f64; 2]],
    x: &mut [[f64; 2]],
    tolerance: f64,
    max_iterations: usize,
    give_up: bool,
) -> CgOutcome {
    let n = b.len();
    let dot = |u: &[[f64; 2]], v: &[[f64; 2]]| u.iter().zip(v).fold([0.0; 2], |s, (p, q)| [s[0] + p[0] * q[0], s[1] + p[1] * q[1]]);
    let inverse: Vec<f64> = diagonal.iter().map(|&d| 1.0 / d).collect();
    if inverse.iter().any(|d| !(d.is_finite() && *d > 0.0)) {
        return CgOutcome { iterations: 0, converged: false };
    }
    let b_norm = dot(b, b).map(f64::sqrt);
    let mut ap = vec![[0.0; 2]; n];
    apply(x, &mut ap);
    let mut r: Vec<[f64; 2]> = b.iter().zip(&ap).map(|(b, a)| [b[0] - a[0], b[1] - a[1]]).collect();
    let mut z: Vec<[f64; 2]> = r.iter().zip(&inverse).map(|(r, d)| [r[0] * d, r[1] * d]).collect();
    let mut p = z.clone();
    let mut rz = dot(&r, &z);
    let done = |r: &[[f64; 2]]| {
        let rr = dot(r, r);
        (0..2).all(|k| rr[k].sqrt() <= tolerance * b_norm[k])
    };
    // Residual norms at the start of the current stagnation window.
    let mut window_start = dot(&r, &r).map(f64::sqrt);
    for iteration in 0..max_iterations {
        if done(&r) {
            return CgOutcome { iterations: iteration, converged: true };
        }
        if give_up && iteration > 0 && iteration % STAGNATION_WINDOW == 0 {
            let now = dot(&r, &r).map(f64::sqrt);
            if iteration >= 2 * STAGNATION_WINDOW && (0..2).any(|k| out_of_reach(window_start[k], now[k], tolerance * b_norm[k], iteration, max_iterations)) {
                return CgOutcome { iterations: iteration, converged: false };
            }
            window_start = now;
        }
        apply(&p, &mut ap);
        let curvature = dot(&p, &ap);
        // A column already solved has p = 0: its step stays 0.
        let mut step = [0.0; 2];
        for k in 0..2 {
            if rz[k] != 0.0 {
                if !(curvature[k] > 0.0) {
                    return CgOutcome { iterations: iteration, converged: false };
                }
                step[k] = rz[k] / curvature[k];
            }
        }
        for i in 0..n {
            for k in 0..2 {
                x[i][k] += step[k] * p[i][k];
                r[i][k] -= step[k] * ap[i][k];
                z[i][k] = r[i][k] * inverse[i];
            }
        }
        let rz_next = dot(&r, &z);
        let ratio = [0, 1].map(|k| if rz[k] != 0.0 { rz_next[k] / rz[k] } else { 0.0 });
        for i in 0..n {
            for k in 0..2 {
                p[i][k] = z[i][k] + ratio[k] * p[i][k];
            }
        }
        rz = rz_next;
    }
    CgOutcome { iterations: max_iterations, converged: done(&r) }
}

/// Whether a residual that went from `before` to `now` over the last [`STAGNATION_WINDOW`]
/// iterations, decreasing at that rate, would still be above `goal` after `max_iterations`
/// (it has made `iteration`).
fn out_of_reach(before: f64, now: f64, goal: f64, iteration: usize, max_iterations: usize) -> bool {
    if now <= goal {
        return false;
    }
    let (gain, need) = ((before / now).ln(), (now / goal).ln());
    !(gain > 0.0) || iteration as f64 + STAGNATION_WINDOW as f64 * need / gain > max_iterations as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `A = diag(m) + L` for the path graph's Laplacian `L` (weights `w`), a tridiagonal SPD
    /// matrix, and its product.
    #[allow(clippy::type_complexity)]
    fn path_system<'a>(m: &[f64], w: &'a [f64]) -> (Vec<f64>, impl Fn(&[[f64; 2]], &mut [[f64; 2]]) + 'a) {
        let n = m.len();
        let mut diagonal = m.to_vec();
        for (i, &wi) in w.iter().enumerate() {
            diagonal[i] += wi;
            diagonal[i + 1] += wi;
        }
        let d = diagonal.clone();
        let apply = move |x: &[[f64; 2]], y: &mut [[f64; 2]]| {
            for i in 0..n {
                y[i] = [d[i] * x[i][0], d[i] * x[i][1]];
            }
            for (i, &wi) in w.iter().enumerate() {
                for k in 0..2 {
                    y[i][k] -= wi * x[i + 1][k];
                    y[i + 1][k] -= wi * x[i][k];
                }
            }
        };
        (diagonal, apply)
    }

    #[test]
    fn solves_a_tridiagonal_system_like_the_thomas_algorithm() {
        let n = 200;
        let m: Vec<f64> = (0..n).map(|i| 0.01 + (i % 7) as f64 * 0.1).collect();
        let w: Vec<f64> = (0..n - 1).map(|i| 1.0 + (i % 5) as f64).collect();
        let b: Vec<[f64; 2]> = (0..n).map(|i| [(i as f64 * 0.3).sin(), 1.0]).collect();
        let (diagonal, apply) = path_system(&m, &w);
        // The exact solution by Gaussian elimination on the tridiagonal matrix.
        let exact: Vec<[f64; 2]> = {
            let (mut c, mut d) = (vec![0.0; n], vec![[0.0; 2]; n]);
            for i in 0..n {
                let lower = if i > 0 { -w[i - 1] } else { 0.0 };
                let upper = if i + 1 < n { -w[i] } else { 0.0 };
                let pivot = diagonal[i] - lower * if i > 0 { c[i - 1] } else { 0.0 };
                c[i] = upper / pivot;
                for k in 0..2 {
                    d[i][k] = (b[i][k] - lower * if i > 0 { d[i - 1][k] } else { 0.0 }) / pivot;
                }
            }
            for i in (0..n - 1).rev() {
                for k in 0..2 {
                    d[i][k] -= c[i] * d[i + 1][k];
                }
            }
            d
        };
        let mut x = vec![[0.0; 2]; n];
        let out = jacobi_cg2(&apply, &diagonal, &b, &mut x, 1e-12, 1000);
        assert!(out.converged && out.iterations > 1, "{out:?}");
        let scale = exact.iter().map(|e| e[0].abs().max(e[1].abs())).fold(0.0, f64::max);
        for (a, e) in x.iter().zip(&exact) {
            assert!((a[0] - e[0]).abs() < 1e-9 * scale && (a[1] - e[1]).abs() < 1e-9 * scale, "{a:?} vs {e:?}");
        }
        // Started at the solution it stops at once; with too few iterations it says so.
        let mut at = exact.clone();
        assert_eq!(jacobi_cg2(&apply, &diagonal, &b, &mut at, 1e-8, 1000), CgOutcome { iterations: 0, converged: true });
        let mut short = vec![[0.0; 2]; n];
        assert!(!jacobi_cg2(&apply, &diagonal, &b, &mut short, 1e-12, 3).converged);
    }

    /// A long path with tiny masses converges slowly (its smallest eigenvalue is the masses'):
    /// the plain solve makes every iteration allowed, the giving-up solve stops once the
    /// rate shows the tolerance out of reach, with the same iterate as the plain solve
    /// stopped there; a system it can solve it solves as the plain one does.
    #[test]
    fn gives_up_on_a_stalled_solve_and_not_on_a_converging_one() {
        let n = 2000;
        let m = vec![1e-6; n];
        let w = vec![1.0; n - 1];
        let b: Vec<[f64; 2]> = (0..n).map(|i| [1e-6 * (i as f64 * 0.01).sin(), 1e-6]).collect();
        let (diagonal, apply) = path_system(&m, &w);
        let mut plain = vec![[0.0; 2]; n];
        assert_eq!(jacobi_cg2(&apply, &diagonal, &b, &mut plain, 1e-10, 400), CgOutcome { iterations: 400, converged: false });
        let mut early = vec![[0.0; 2]; n];
        let out = jacobi_cg2_or_give_up(&apply, &diagonal, &b, &mut early, 1e-10, 400);
        assert!(!out.converged && out.iterations < 400 && out.iterations % STAGNATION_WINDOW == 0, "{out:?}");
        let mut same = vec![[0.0; 2]; n];
        jacobi_cg2(&apply, &diagonal, &b, &mut same, 1e-10, out.iterations);
        assert_eq!(early, same);
        // Masses of 0.02: converging steadily, solved by both alike.
        let (diagonal, apply) = path_system(&vec![0.02; n], &w);
        let (mut x, mut y) = (vec![[0.0; 2]; n], vec![[0.0; 2]; n]);
        let out = jacobi_cg2_or_give_up(&apply, &diagonal, &b, &mut x, 1e-10, 400);
        assert!(out.converged && out.iterations > 2 * STAGNATION_WINDOW, "{out:?}");
        assert_eq!(jacobi_cg2(&apply, &diagonal, &b, &mut y, 1e-10, 400), out);
        assert_eq!(x, y);
    }

    #[test]
    fn refuses_an_indefinite_matrix_and_a_bad_diagonal() {
        // diag(1, -1): p . A p <= 0 for the second coordinate's direction.
        let diagonal = [1.0, -1.0];
        let apply = |x: &[[f64; 2]], y: &mut [[f64; 2]]| {
            y[0] = x[0];
            y[1] = [-x[1][0], -x[1][1]];
        };
        let mut x = vec![[0.0; 2]; 2];
        assert!(!jacobi_cg2(apply, &diagonal, &[[1.0, 1.0], [1.0, 1.0]], &mut x, 1e-10, 10).converged);
        // [[1, 3], [3, 1]] has eigenvalues 4 and -2; (1, -1) is the negative one's vector.
        let apply = |x: &[[f64; 2]], y: &mut [[f64; 2]]| {
            y[0] = [x[0][0] + 3.0 * x[1][0], x[0][1] + 3.0 * x[1][1]];
            y[1] = [3.0 * x[0][0] + x[1][0], 3.0 * x[0][1] + x[1][1]];
        };
        let mut x = vec![[0.0; 2]; 2];
        let out = jacobi_cg2(apply, &[1.0, 1.0], &[[1.0, 1.0], [-1.0, -1.0]], &mut x, 1e-10, 10);
        assert_eq!(out, CgOutcome { iterations: 0, converged: false });
    }
}
