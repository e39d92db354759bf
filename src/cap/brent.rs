//! Brent's bounded scalar minimiser (golden section with parabolic interpolation), the method
//! of MATLAB's `fminbnd` that the paper uses for the radius search (Sec. 4).

/// Minimise `f` on `[a, b]` to absolute tolerance `xtol`. `f` may fail; the first error
/// stops the search. Returns the best point and value seen.
pub fn minimize<E>(f: impl FnMut(f64) -> Result<f64, E>, a: f64, b: f64, xtol: f64, max_evals: usize) -> Result<(f64, f64), E> {
    minimize_with_tolerance(f, a, b, |_| xtol, max_evals, false)
}

/// [`minimize`] with a tolerance that depends on the point: the search stops when the
/// bracket around the best point `x` is within `xtol(x)`. A search over a transformed
/// variable uses it to keep its tolerance in the original one.
///
/// Ours on top of Brent's method, when `bound_probe` is set: a *bound probe*. Brent's method
/// reaches a minimum at a bound only by steps that shrink geometrically towards it (the
/// closed surfaces' radius search, whose energy falls all the way to `Z* = -0.995`, spent 6-7
/// of its 10-11 solves creeping there). When two successive improvements have moved towards
/// a bound that is still an end of the bracket and the parabola through the last three
/// points has no minimum inside the bracket away from that bound (or three improvements
/// have), the points one and two tolerances inside the bound are evaluated; for a unimodal
/// function the second settles the search when the first is the best point. A failed probe
/// only narrows the bracket, and is not repeated, but it costs an evaluation far from the
/// minimum (and, in the radius search, a warm start from there): on the open surfaces'
/// interior minima it fired and missed (hand: 37 -> 49 search iterations, LV endocardium
/// 32 -> 45), so only the closed surfaces' search uses it.
pub fn minimize_with_tolerance<E>(
    mut f: impl FnMut(f64) -> Result<f64, E>,
    a: f64,
    b: f64,
    xtol: impl Fn(f64) -> f64,
    max_evals: usize,
    bound_probe: bool,
) -> Result<(f64, f64), E> {
    let golden = 0.5 * (3.0 - 5f64.sqrt());
    let (a, b) = (a.min(b), a.max(b));
    let (lower, upper) = (a, b);
    let x = a + golden * (b - a);
    let fx = f(x)?;
    let mut s = Bracket { a, b, x, w: x, v: x, fx, fw: fx, fv: fx };
    let (mut d, mut e): (f64, f64) = (0.0, 0.0);
    let mut evals = 1;
    // Successive improvements towards the lower (-1) or upper (+1) bound.
    let (mut streak, mut towards) = (0usize, 0i8);
    let mut probed = false;
    while evals < max_evals {
        let x = s.x;
        let xm = 0.5 * (s.a + s.b);
        let tol1 = step_tolerance(x, &xtol);
        let tol2 = 2.0 * tol1;
        if (x - xm).abs() <= tol2 - 0.5 * (s.b - s.a) {
            break;
        }
        if bound_probe && !probed && streak >= 2 && evals + 2 <= max_evals {
            let bound = if towards < 0 { lower } else { upper };
            let still_bracketed = if towards < 0 { s.a == lower } else { s.b == upper };
            let t = step_tolerance(bound, &xtol);
            let inward = if towards < 0 { 1.0 } else { -1.0 };
            let creeping = streak >= 3 || !s.predicts_minimum_away_from(bound, 2.0 * t);
            if still_bracketed && creeping && (x - bound).abs() > 2.0 * t {
                probed = true;
                let u1 = bound + inward * t;
                let fu1 = f(u1)?;
                evals += 1;
                let improved = s.accept(u1, fu1);
                if improved {
                    let u2 = bound + inward * 2.0 * t;
                    let fu2 = f(u2)?;
                    evals += 1;
                    s.accept(u2, fu2);
                }
                // The next step is a golden one (no parabola through the far-apart points).
                e = 0.0;
                continue;
            }
        }
        let mut golden_step = true;
        if e.abs() > tol1 {
            // Parabola through x, w, v.
            let r = (x - s.w) * (s.fx - s.fv);
            let mut q = (x - s.v) * (s.fx - s.fw);
            let mut p = (x - s.v) * q - (x - s.w) * r;
            q = 2.0 * (q - r);
            if q > 0.0 {
                p = -p;
            }
            q = q.abs();
            let e_old = e;
            if p.abs() < (0.5 * q * e_old).abs() && p > q * (s.a - x) && p < q * (s.b - x) {
                e = d;
                d = p / q;
                let u = x + d;
                if u - s.a < tol2 || s.b - u < tol2 {
                    d = if xm >= x { tol1 } else { -tol1 };
                }
                golden_step = false;
            }
        }
        if golden_step {
            e = if x >= xm { s.a - x } else { s.b - x };
            d = golden * e;
        }
        let u = if d.abs() >= tol1 { x + d } else if d > 0.0 { x + tol1 } else { x - tol1 };
        let fu = f(u)?;
        evals += 1;
        if s.accept(u, fu) {
            let dir = if u < x { -1 } else { 1 };
            streak = if dir == towards { streak + 1 } else { 1 };
            towards = dir;
        } else {
            streak = 0;
        }
    }
    Ok((s.x, s.fx))
}

/// Brent's smallest step at `x` (his `tol1`: a relative `1e-10` and a third of the
/// tolerance there); the bound probe's points are one and two of them inside the bound.
fn step_tolerance(x: f64, xtol: &impl Fn(f64) -> f64) -> f64 {
    1e-10 * x.abs() + xtol(x) / 3.0
}

/// The closed surfaces' radius search (ours): Brent's method with the bound probe, but the
/// probe taken first. The points one and two tolerances inside the `lower` bound are
/// evaluated before anything else; when the first is no worse than the second, the search
/// ends at the first: for a unimodal function the minimum then lies within two tolerances of
/// the bound, which is what the probe concludes after Brent's approach. Otherwise the two
/// evaluations are spent and [`minimize_with_tolerance`] runs with the probe as before.
/// The closed surfaces' energy falls all the way to the bound on every mesh measured, and
/// the approach cost 5 of their 7 transport solves, the first of them cold (see
/// [`crate::param::parameterize()`]).
pub fn minimize_from_lower_bound<E>(
    mut f: impl FnMut(f64) -> Result<f64, E>,
    lower: f64,
    upper: f64,
    xtol: impl Fn(f64) -> f64,
    max_evals: usize,
) -> Result<(f64, f64), E> {
    let (lower, upper) = (lower.min(upper), lower.max(upper));
    let t = step_tolerance(lower, &xtol);
    if max_evals >= 2 && upper - lower > 4.0 * t {
        let (u1, u2) = (lower + t, lower + 2.0 * t);
        let f1 = f(u1)?;
        let f2 = f(u2)?;
        if f1 <= f2 {
            return Ok((u1, f1));
        }
        return minimize_with_tolerance(f, lower, upper, xtol, max_evals - 2, true);
    }
    minimize_with_tolerance(f, lower, upper, xtol, max_evals, true)
}

/// Brent's state: the bracket `[a, b]`, the best point `x`, the second best `w` and the
/// previous `w`, `v`, with their values.
struct Bracket {
    a: f64,
    b: f64,
    x: f64,
    w: f64,
    v: f64,
    fx: f64,
    fw: f64,
    fv: f64,
}

impl Bracket {
    /// Take the evaluation `f(u) = fu` into the bracket; `true` when `u` is the new best.
    fn accept(&mut self, u: f64, fu: f64) -> bool {
        if fu <= self.fx {
            if u >= self.x {
                self.a = self.x;
            } else {
                self.b = self.x;
            }
            self.v = self.w;
            self.fv = self.fw;
            self.w = self.x;
            self.fw = self.fx;
            self.x = u;
            self.fx = fu;
            true
        } else {
            if u < self.x {
                self.a = u;
            } else {
                self.b = u;
            }
            if fu <= self.fw || self.w == self.x {
                self.v = self.w;
                self.fv = self.fw;
                self.w = u;
                self.fw = fu;
            } else if fu <= self.fv || self.v == self.x || self.v == self.w {
                self.v = u;
                self.fv = fu;
            }
            false
        }
    }

    /// Whether the parabola through `x`, `w` and `v` is convex with its vertex inside the
    /// bracket more than `margin` away from `bound` (`false` without three distinct points).
    fn predicts_minimum_away_from(&self, bound: f64, margin: f64) -> bool {
        let (x0, x1, x2) = (self.v, self.w, self.x);
        let (f0, f1, f2) = (self.fv, self.fw, self.fx);
        if x0 == x1 || x1 == x2 || x0 == x2 {
            return false;
        }
        // Second divided difference: positive for a convex parabola.
        let d01 = (f1 - f0) / (x1 - x0);
        let d12 = (f2 - f1) / (x2 - x1);
        let curvature = (d12 - d01) / (x2 - x0);
        if !(curvature > 0.0) {
            return false;
        }
        // Vertex of f0 + d01 (t - x0) + curvature (t - x0)(t - x1).
        let vertex = 0.5 * (x0 + x1) - d01 / (2.0 * curvature);
        vertex > self.a && vertex < self.b && (vertex - bound).abs() > margin
    }
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
        let (x, _) = minimize::<()>(Ok, -1.0, 1.0, 1e-4, 60).unwrap();
        assert!(x < -0.999);
    }

    #[test]
    fn a_looser_tolerance_away_from_the_origin_stops_sooner_at_the_same_place() {
        // An interior minimum near the bound of [-3, 3], where cosh^2 is large (not a
        // parabola, which Brent's method would find exactly with any tolerance).
        let count = |tol: &dyn Fn(f64) -> f64| {
            let mut n = 0;
            let (x, _) = minimize_with_tolerance::<()>(|x| { n += 1; Ok((x + 2.5).abs().powf(1.5)) }, -3.0, 3.0, tol, 60, false).unwrap();
            (x, n)
        };
        let (x_fixed, n_fixed) = count(&|_| 1e-3);
        let (x_loose, n_loose) = count(&|x: f64| 1e-3 * x.cosh().powi(2));
        assert!((x_fixed + 2.5).abs() < 1e-3 && (x_loose + 2.5).abs() < 1e-3 * 2.5f64.cosh().powi(2), "{x_fixed} {x_loose}");
        assert!(n_loose < n_fixed, "{n_loose} evaluations, {n_fixed} with the fixed tolerance");
    }

    /// The minimum of `f` on `[a, b]` to tolerance `tol` and the evaluations it took, with or
    /// without the bound probe.
    fn evaluations(f: impl Fn(f64) -> f64, a: f64, b: f64, tol: f64, probe: bool) -> (f64, usize) {
        let mut n = 0;
        let (x, _) = minimize_with_tolerance::<()>(|x| { n += 1; Ok(f(x)) }, a, b, |_| tol, 100, probe).unwrap();
        (x, n)
    }

    #[test]
    fn a_minimum_at_the_bound_is_reached_sooner_by_the_probe() {
        // Decreasing all the way to a bound, like the closed surfaces' radius energy.
        // Each case: a function decreasing towards one end of [-3, 3], and that end.
        type Case = (fn(f64) -> f64, f64);
        let cases: [Case; 4] = [(|x| x, -3.0), (|x| (x + 3.0).sqrt(), -3.0), (|x| (2.0 * x).exp(), -3.0), (|x| -x.powi(3), 3.0)];
        for (f, bound) in cases {
            let (x, n) = evaluations(f, -3.0, 3.0, 1e-3, true);
            let (x_plain, n_plain) = evaluations(f, -3.0, 3.0, 1e-3, false);
            assert!((x - bound).abs() <= 1e-3 && (x_plain - bound).abs() <= 1e-3, "x = {x}, {x_plain} without the probe");
            assert!(n + 2 <= n_plain, "{n} evaluations, {n_plain} without the probe");
        }
    }

    #[test]
    fn the_lower_bound_first_settles_a_decreasing_function_in_two_evaluations() {
        let tol = 1e-3;
        // Decreasing towards the lower bound: two evaluations, the same place as the search
        // with the probe reaches after its approach.
        for f in [(|x| x) as fn(f64) -> f64, |x| (x + 3.0).sqrt(), |x| (2.0 * x).exp()] {
            let mut n = 0;
            let (x, _) = minimize_from_lower_bound::<()>(|x| { n += 1; Ok(f(x)) }, -3.0, 3.0, |_| tol, 100).unwrap();
            let (x_probe, n_probe) = evaluations(f, -3.0, 3.0, tol, true);
            assert_eq!(n, 2);
            assert!(n_probe > 4, "{n_probe}");
            assert!((x + 3.0).abs() <= tol && (x - x_probe).abs() <= tol, "x = {x}, {x_probe} with the probe after the approach");
        }
        // Minima elsewhere: the two evaluations are spent, then found as by the search.
        for (f, at) in [((|x| (x - 0.3).powi(2)) as fn(f64) -> f64, 0.3), (|x| (x + 2.9).powi(2), -2.9), (|x| -x.powi(3), 3.0)] {
            let mut n = 0;
            let (x, _) = minimize_from_lower_bound::<()>(|x| { n += 1; Ok(f(x)) }, -3.0, 3.0, |_| tol, 100).unwrap();
            let (_, n_probe) = evaluations(f, -3.0, 3.0, tol, true);
            assert!((x - at).abs() <= tol, "x = {x}, minimum at {at}");
            assert_eq!(n, n_probe + 2);
        }
    }

    #[test]
    fn interior_minima_near_a_bound_are_still_found() {
        // A quadratic: the parabola sees the minimum, no probe.
        let (x, _) = evaluations(|x| (x + 2.9).powi(2), -3.0, 3.0, 1e-3, true);
        assert!((x + 2.9).abs() < 1e-3, "x = {x}");
        // A cusp the parabolas cannot see: the probe is taken, the search goes on from there.
        let (x, _) = evaluations(|x| (x + 2.99).abs().sqrt(), -3.0, 3.0, 1e-3, true);
        assert!((x + 2.99).abs() < 1e-3, "x = {x}");
        // A minimum well inside: found as before.
        let (x, _) = evaluations(|x| (x - 0.3).powi(2) + 0.1 * (x - 0.3).powi(4), -0.995, 0.995, 1e-4, true);
        assert!((x - 0.3).abs() < 1e-4, "x = {x}");
    }
}
