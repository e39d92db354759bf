//! The range of every number in [`ParamOptions`]: a NaN or negative tolerance set from Rust
//! would otherwise reach the solvers and come back as a misleading failure (a NaN transport
//! tolerance used to be reported as a surface too elongated to map, after six attempts).

use super::ParamOptions;
use crate::refine::Smoothing;

/// `Ok` if `x` is a finite number > 0, else the message naming `name`.
fn positive(name: &str, x: f64) -> Result<(), String> {
    if x.is_finite() && x > 0.0 {
        Ok(())
    } else {
        Err(format!("{name} = {x} is not a finite number > 0"))
    }
}

/// `Ok` if `x` is a number >= 0 (infinity allowed when `infinite`), else the message naming `name`.
fn non_negative(name: &str, x: f64, infinite: bool) -> Result<(), String> {
    if x >= 0.0 && (infinite || x.is_finite()) {
        Ok(())
    } else {
        Err(format!("{name} = {x} is not a {}number >= 0", if infinite { "" } else { "finite " }))
    }
}

/// `Ok` if `x` is in `[lo, hi]`, else the message naming `name`.
fn within(name: &str, x: f64, lo: f64, hi: f64) -> Result<(), String> {
    if (lo..=hi).contains(&x) {
        Ok(())
    } else {
        Err(format!("{name} = {x} is outside [{lo}, {hi}]"))
    }
}

impl ParamOptions {
    /// `Ok` unless a number is out of its range, else the field (as its path in these options,
    /// e.g. `transport.tolerance`), its value and the range. [`parameterize`](crate::param::parameterize)
    /// and [`remesh`](crate::remesh::remesh) refuse options that fail it before any work.
    pub fn check(&self) -> Result<(), String> {
        self.domain.check()?;
        non_negative("weld_tolerance", self.weld_tolerance, false)?;
        let t = &self.transport;
        positive("transport.tolerance", t.tolerance)?;
        if !(t.min_step > 0.0 && t.min_step <= 1.0) {
            return Err(format!("transport.min_step = {} is outside (0, 1]", t.min_step));
        }
        non_negative("transport.log_step_error", t.log_step_error, true)?;
        if !(t.log_step_shrink > 0.0 && t.log_step_shrink < 1.0) {
            return Err(format!("transport.log_step_shrink = {} is outside (0, 1)", t.log_step_shrink));
        }
        non_negative("transport.stale_step_error", t.stale_step_error, true)?;
        positive("search.z_tolerance", self.search.z_tolerance)?;
        positive("search.tolerance", self.search.tolerance)?;
        within("open.lambda", self.open.lambda, 0.0, 1.0)?;
        positive("open.conformal.tolerance", self.open.conformal.tolerance)?;
        let flatten = &self.closed.flatten;
        within("closed.flatten.lambda", flatten.lambda, 0.0, 1.0)?;
        for &lambda in &self.closed.lambda_fallbacks {
            within("closed.lambda_fallbacks", lambda, 0.0, 1.0)?;
        }
        non_negative("closed.flatten.stretch.tolerance", flatten.stretch.tolerance, false)?;
        positive("closed.flatten.stretch.over_relaxation", flatten.stretch.over_relaxation)?;
        positive("closed.flatten.puncture.max_ratio", flatten.puncture.max_ratio)?;
        positive("closed.flatten.puncture.acceptable_ratio", flatten.puncture.acceptable_ratio)?;
        non_negative("closed.flatten.puncture.reach", flatten.puncture.reach, false)?;
        match self.refinement.smoothing {
            Smoothing::Fixed(kappa) => non_negative("refinement.smoothing", kappa, false),
            Smoothing::Auto => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A message's start and the change of the default options that should cause it.
    type Case = (&'static str, fn(&mut ParamOptions));

    #[test]
    fn defaults_pass_and_each_bad_number_is_named() {
        let default = ParamOptions::default();
        assert_eq!(default.check(), Ok(()));
        let cases: [Case; 6] = [
            ("transport.tolerance = NaN", |o| o.transport.tolerance = f64::NAN),
            ("search.z_tolerance = NaN", |o| o.search.z_tolerance = f64::NAN),
            ("weld_tolerance = -1", |o| o.weld_tolerance = -1.0),
            ("open.lambda = 2", |o| o.open.lambda = 2.0),
            ("closed.lambda_fallbacks = NaN", |o| o.closed.lambda_fallbacks = vec![0.5, f64::NAN]),
            ("refinement.smoothing = inf", |o| o.refinement.smoothing = Smoothing::Fixed(f64::INFINITY)),
        ];
        for (named, set) in cases {
            let mut o = default.clone();
            set(&mut o);
            let message = o.check().unwrap_err();
            assert!(message.starts_with(named), "{named}: {message}");
        }
        // Infinity is the documented "plain steps only" for the logarithmic steps' bound.
        let mut plain = default.clone();
        plain.transport.log_step_error = f64::INFINITY;
        assert_eq!(plain.check(), Ok(()));
    }
}
