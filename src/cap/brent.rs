//! Brent's bounded scalar minimiser (golden section with parabolic interpolation), the method
//! of MATLAB's `fminbnd` that the paper uses for the radius search (Sec. 4).

/// Minimise `f` on `[a, b]` to absolute tolerance `xtol`. `f` may fail; the first error
/// stops the search. Returns the best point and value seen.
pub fn minimize<E>(f: impl FnMut(f64) -> Result<f64, E>, a: f64, b: f64, xtol: f64, max_evals: usize) -> Result<(f64, f64), E> {
    minimize_with_tolerance(f, a, b, |_| xtol, max_evals)
}

/// [`minimize`] with a tolerance that depends on the point: the search stops when the
/// bracket around the best point `x` is within `xtol(x)`. A search over a transformed
/// variable uses it to keep its tolerance in the original one.
pub fn minimize_with_tolerance<E>(
    mut f: impl FnMut(f64) -> Result<f64, E>,
    a: f64,
    b: f64,
    xtol: impl Fn(f64) -> f64,
    max_evals: usize,
) -> Result<(f64, f64), E> {
    let golden = 0.5 * (3.0 - 5f64.sqrt());
    let (mut a, mut b) = (a.min(b), a.max(b));
    let mut x = a + golden * (b - a);
    let (mut w, mut v) = (x, x);
    let mut fx = f(x)?;
    let (mut fw, mut fv) = (fx, fx);
    let (mut d, mut e): (f64, f64) = (0.0, 0.0);
    let mut evals = 1;
    while evals < max_evals {
        let xm = 0.5 * (a + b);
        let tol1 = 1e-10 * x.abs() + xtol(x) / 3.0;
        let tol2 = 2.0 * tol1;
        if (x - xm).abs() <= tol2 - 0.5 * (b - a) {
            break;
        }
        let mut golden_step = true;
        if e.abs() > tol1 {
            // Parabola through x, w, v.
            let r = (x - w) * (fx - fv);
            let mut q = (x - v) * (fx - fw);
            let mut p = (x - v) * q - (x - w) * r;
            q = 2.0 * (q - r);
            if q > 0.0 {
                p = -p;
            }
            q = q.abs();
            let e_old = e;
            if p.abs() < (0.5 * q * e_old).abs() && p > q * (a - x) && p < q * (b - x) {
                e = d;
                d = p / q;
                let u = x + d;
                if u - a < tol2 || b - u < tol2 {
                    d = if xm >= x { tol1 } else { -tol1 };
                }
                golden_step = false;
            }
        }
        if golden_step {
            e = if x >= xm { a - x } else { b - x };
            d = golden * e;
        }
        let u = if d.abs() >= tol1 { x + d } else if d > 0.0 { x + tol1 } else { x - tol1 };
        let fu = f(u)?;
        evals += 1;
        if fu <= fx {
            if u >= x {
                a = x;
            } else {
                b = x;
            }
            v = w;
            fv = fw;
            w = x;
            fw = fx;
            x = u;
            fx = fu;
        } else {
            if u < x {
                a = u;
            } else {
                b = u;
            }
            if fu <= fw || w == x {
                v = w;
                fv = fw;
                w = u;
                fw = fu;
            } else if fu <= fv || v == x || v == w {
                v = u;
                fv = fu;
            }
        }
    }
    Ok((x, fx))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_minimum_of_smooth_function() {
        let mut n = 0;
        let (x, fx) = minimize::<()>(|x| { n += 1; Ok((x - 0.3).powi(2) + 1.0 + 0.1 * (x - 0.3).powi(4)) }, -0.995, 0.995, 1e-4, 50).unwrap();
        assert!((x - 0.3).abs() < 1e-3, "x = {x}");
        assert!((fx - 1.0).abs() < 1e-6);
        assert!(n < 30);
        // Minimum at the bound.
        let (x, _) = minimize::<()>(|x| Ok(x), -1.0, 1.0, 1e-4, 60).unwrap();
        assert!(x < -0.999);
    }

    #[test]
    fn a_looser_tolerance_away_from_the_origin_stops_sooner_at_the_same_place() {
        // f(x) = x on [-3, 3]: the minimum is at the bound -3.
        let count = |tol: &dyn Fn(f64) -> f64| {
            let mut n = 0;
            let (x, _) = minimize_with_tolerance::<()>(|x| { n += 1; Ok(x) }, -3.0, 3.0, tol, 60).unwrap();
            (x, n)
        };
        let (x_fixed, n_fixed) = count(&|_| 1e-3);
        let (x_loose, n_loose) = count(&|x: f64| 1e-3 * x.cosh().powi(2));
        assert!(x_fixed < -3.0 + 2e-3 && x_loose < -3.0 + 1e-3 * 3f64.cosh().powi(2), "{x_fixed} {x_loose}");
        assert!(n_loose < n_fixed, "{n_loose} evaluations, {n_fixed} with the fixed tolerance");
    }
}
