//! The cohort comparison of `capmesh::harmonics::cohort`: Welch's t-test against a textbook
//! example's published figures (the two 15-value samples of Wikipedia's "Welch's t-test",
//! Example 1: t = -2.46, df = 25.0, p = 0.021) and against an independent numerical
//! integration of the t density; group summaries; the refusals.

use capmesh::harmonics::{compare_groups, welch_t_test, CohortError};

const A1: [f64; 15] = [27.5, 21.0, 19.0, 23.6, 17.0, 17.9, 16.9, 20.1, 21.9, 22.6, 23.1, 19.6, 19.0, 21.7, 21.4];
const A2: [f64; 15] = [27.1, 22.0, 20.8, 23.4, 23.4, 23.5, 25.8, 22.0, 24.8, 20.2, 21.9, 22.1, 22.9, 20.5, 24.4];

/// Two-sided p-value of `t` with `df` degrees of freedom by Simpson's rule on the t density
/// `(1 + x^2 / df)^(-(df + 1) / 2)`, normalized by its own integral over [0, 200] plus the tail
/// in closed form (no gamma function, no library): independent of statrs.
fn p_by_integration(t: f64, df: f64) -> f64 {
    let density = |x: f64| (1.0 + x * x / df).powf(-(df + 1.0) / 2.0);
    let simpson = |a: f64, b: f64, n: usize| {
        let h = (b - a) / n as f64;
        let inner: f64 = (1..n).map(|i| if i % 2 == 1 { 4.0 } else { 2.0 } * density(a + i as f64 * h)).sum();
        (density(a) + density(b) + inner) * h / 3.0
    };
    // Beyond x = 200 the density is ~ df^((df+1)/2) x^-(df+1): its tail integral in closed form.
    let tail = |x: f64| df.powf((df + 1.0) / 2.0) * x.powf(-df) / df;
    let total = simpson(0.0, 200.0, 400_000) + tail(200.0);
    2.0 * (total - simpson(0.0, t.abs(), 200_000)) / (2.0 * total)
}

#[test]
fn welch_matches_the_textbook_example() {
    let w = welch_t_test("A1", &A1, "A2", &A2).unwrap();
    eprintln!("{w:?}");
    // The published figures, to the digits printed.
    assert_eq!(format!("{:.2}", w.t), "-2.46");
    assert_eq!(format!("{:.1}", w.degrees_of_freedom), "25.0");
    assert_eq!(format!("{:.3}", w.p_value), "0.021");
    // Hand-computed from the sample means 20.82 and 22.9867 and variances 7.86743 and 3.81267.
    assert!((w.mean_difference + 2.166_666_666_666_67).abs() < 1e-9, "{}", w.mean_difference);
    assert!((w.t + 2.455_356_398_286).abs() < 1e-9, "{}", w.t);
    assert!((w.degrees_of_freedom - 24.988_529_290_231).abs() < 1e-8, "{}", w.degrees_of_freedom);
    // Cohen's d with the pooled standard deviation sqrt((7.86743 + 3.81267) / 2).
    let pooled = ((7.867_428_571_428_57 + 3.812_666_666_666_67) / 2.0f64).sqrt();
    assert!((w.cohen_d + 2.166_666_666_666_67 / pooled).abs() < 1e-9, "{}", w.cohen_d);
    // The p-value against an independent integration of the t density.
    let independent = p_by_integration(w.t, w.degrees_of_freedom);
    assert!((w.p_value - independent).abs() < 1e-6, "statrs {} vs integration {independent}", w.p_value);
    // Swapping the groups flips the sign only.
    let back = welch_t_test("A2", &A2, "A1", &A1).unwrap();
    assert!((back.t + w.t).abs() < 1e-12 && (back.p_value - w.p_value).abs() < 1e-15);
}

#[test]
fn groups_are_summarized_and_every_pair_tested() {
    let mut samples: Vec<(String, f64)> = A1.iter().map(|&v| ("demented".to_string(), v)).collect();
    samples.extend(A2.iter().map(|&v| ("non-demented".to_string(), v)));
    samples.extend([1.0, 2.0, 3.0].iter().map(|&v| ("third".to_string(), v)));
    let c = compare_groups(&samples).unwrap();
    let names: Vec<&str> = c.groups.iter().map(|g| g.group.as_str()).collect();
    assert_eq!(names, ["demented", "non-demented", "third"]);
    assert_eq!(c.groups[0].count, 15);
    assert!((c.groups[0].mean - 20.82).abs() < 1e-12);
    assert!((c.groups[0].std_dev - 7.867_428_571_428_57f64.sqrt()).abs() < 1e-12);
    assert_eq!((c.groups[2].min, c.groups[2].max, c.groups[2].std_dev), (1.0, 3.0, 1.0));
    let pairs: Vec<(&str, &str)> = c.tests.iter().map(|t| (t.first.as_str(), t.second.as_str())).collect();
    assert_eq!(pairs, [("demented", "non-demented"), ("demented", "third"), ("non-demented", "third")]);
    assert_eq!(c.tests[0], welch_t_test("demented", &A1, "non-demented", &A2).unwrap());
    assert!(c.tests[1].p_value < 1e-3, "a clear difference has a small p-value: {:?}", c.tests[1]);
}

#[test]
fn bad_groups_are_refused_with_the_reason() {
    let one = welch_t_test("a", &[1.0], "b", &[1.0, 2.0]).unwrap_err();
    assert_eq!(one, CohortError::TooFewValues { group: "a".into(), count: 1 });
    assert!(one.to_string().contains("at least 2"), "{one}");
    let single = compare_groups(&[("a".into(), 1.0), ("a".into(), 2.0)]).unwrap_err();
    assert_eq!(single, CohortError::TooFewGroups { groups: 1 });
    assert!(matches!(welch_t_test("a", &[1.0, f64::NAN], "b", &[1.0, 2.0]), Err(CohortError::NonFinite { .. })));
    assert!(matches!(welch_t_test("a", &[1.0, 1.0], "b", &[2.0, 2.0]), Err(CohortError::ZeroVariance { .. })));
}
