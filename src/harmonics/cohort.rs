//! Comparing groups of shapes (paper Sec. "Shape analysis of demented and non-demented cortical
//! surfaces"): the aspect ratios of the meshes of each group, summarized per group and compared
//! two groups at a time by Welch's unequal-variances t-test.
//!
//! For samples `a` (size `n_a`, mean `mean_a`, sample variance `var_a`) and `b`:
//!
//! ```text
//! t  = (mean_a - mean_b) / sqrt(var_a / n_a + var_b / n_b)
//! df = (var_a / n_a + var_b / n_b)^2 / ((var_a / n_a)^2 / (n_a - 1) + (var_b / n_b)^2 / (n_b - 1))
//! p  = 2 P(T_df <= -|t|)                                    (two-sided, Student's t with df)
//! d  = (mean_a - mean_b) / sqrt(((n_a - 1) var_a + (n_b - 1) var_b) / (n_a + n_b - 2))
//! ```
//!
//! (Welch-Satterthwaite degrees of freedom; Cohen's `d` with the pooled standard deviation as
//! the effect size). The t distribution's CDF is `statrs`'s (regularized incomplete beta).
//! Welch's test does not assume equal variances, which the groups of a cohort need not have.

use serde::Serialize;
use statrs::distribution::{ContinuousCDF, StudentsT};
use thiserror::Error;

/// Why groups cannot be compared.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum CohortError {
    /// A group has fewer than two values (no variance).
    #[error("group '{group}' has {count} value(s); Welch's t-test needs at least 2 per group: add meshes to it or leave it out")]
    TooFewValues {
        /// The group.
        group: String,
        /// Its number of values.
        count: usize,
    },
    /// Fewer than two groups.
    #[error("{groups} group(s) given; a comparison needs at least 2 (the groups file's second column names them)")]
    TooFewGroups {
        /// The number of groups.
        groups: usize,
    },
    /// A NaN or infinite value.
    #[error("group '{group}' has a non-finite value ({value}): a degenerate mesh's aspect ratio; leave that mesh out")]
    NonFinite {
        /// The group.
        group: String,
        /// The value.
        value: f64,
    },
    /// Both groups have zero variance: `t` is undefined.
    #[error("groups '{first}' and '{second}' both have zero variance: the t statistic is undefined")]
    ZeroVariance {
        /// First group.
        first: String,
        /// Second group.
        second: String,
    },
}

/// One group's values summarized.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GroupSummary {
    /// The group's name.
    pub group: String,
    /// Number of values.
    pub count: usize,
    /// Their mean.
    pub mean: f64,
    /// Sample standard deviation (divisor `count - 1`).
    pub std_dev: f64,
    /// Standard error of the mean, `std_dev / sqrt(count)`.
    pub std_error: f64,
    /// Smallest value.
    pub min: f64,
    /// Largest value.
    pub max: f64,
}

/// Welch's t-test of two groups.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WelchTest {
    /// The first group.
    pub first: String,
    /// The second group.
    pub second: String,
    /// `mean_first - mean_second`.
    pub mean_difference: f64,
    /// The t statistic.
    pub t: f64,
    /// Welch-Satterthwaite degrees of freedom.
    pub degrees_of_freedom: f64,
    /// Two-sided p-value.
    pub p_value: f64,
    /// Cohen's d with the pooled standard deviation.
    pub cohen_d: f64,
}

/// Every group summarized and every pair of groups tested.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GroupComparison {
    /// The groups in order of first appearance.
    pub groups: Vec<GroupSummary>,
    /// One test per pair `(i, j)`, `i < j`, in that order.
    pub tests: Vec<WelchTest>,
}

/// Summary of one group's `values`.
pub fn summarize(group: &str, values: &[f64]) -> Result<GroupSummary, CohortError> {
    if let Some(&value) = values.iter().find(|v| !v.is_finite()) {
        return Err(CohortError::NonFinite { group: group.into(), value });
    }
    if values.len() < 2 {
        return Err(CohortError::TooFewValues { group: group.into(), count: values.len() });
    }
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let variance = values.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / (n - 1.0);
    let std_dev = variance.sqrt();
    Ok(GroupSummary {
        group: group.into(),
        count: values.len(),
        mean,
        std_dev,
        std_error: std_dev / n.sqrt(),
        min: values.iter().copied().fold(f64::INFINITY, f64::min),
        max: values.iter().copied().fold(f64::NEG_INFINITY, f64::max),
    })
}

/// Welch's t-test of `a` (group `first`) against `b` (group `second`).
pub fn welch_t_test(first: &str, a: &[f64], second: &str, b: &[f64]) -> Result<WelchTest, CohortError> {
    let (sa, sb) = (summarize(first, a)?, summarize(second, b)?);
    welch_from_summaries(&sa, &sb)
}

fn welch_from_summaries(a: &GroupSummary, b: &GroupSummary) -> Result<WelchTest, CohortError> {
    let (na, nb) = (a.count as f64, b.count as f64);
    let (va, vb) = (a.std_dev * a.std_dev / na, b.std_dev * b.std_dev / nb);
    let se2 = va + vb;
    if !(se2 > 0.0) {
        return Err(CohortError::ZeroVariance { first: a.group.clone(), second: b.group.clone() });
    }
    let difference = a.mean - b.mean;
    let t = difference / se2.sqrt();
    let df = se2 * se2 / (va * va / (na - 1.0) + vb * vb / (nb - 1.0));
    let p_value = match StudentsT::new(0.0, 1.0, df) {
        Ok(dist) => (2.0 * dist.cdf(-t.abs())).min(1.0),
        Err(_) => f64::NAN,
    };
    let pooled = (((na - 1.0) * a.std_dev * a.std_dev + (nb - 1.0) * b.std_dev * b.std_dev) / (na + nb - 2.0)).sqrt();
    Ok(WelchTest {
        first: a.group.clone(),
        second: b.group.clone(),
        mean_difference: difference,
        t,
        degrees_of_freedom: df,
        p_value,
        cohen_d: difference / pooled,
    })
}

/// Summaries of the groups of `samples` (`(group, value)` pairs; groups in order of first
/// appearance) and Welch's test of every pair of groups.
pub fn compare_groups(samples: &[(String, f64)]) -> Result<GroupComparison, CohortError> {
    let mut names: Vec<&str> = Vec::new();
    for (g, _) in samples {
        if !names.contains(&g.as_str()) {
            names.push(g);
        }
    }
    if names.len() < 2 {
        return Err(CohortError::TooFewGroups { groups: names.len() });
    }
    let groups = names
        .iter()
        .map(|name| {
            let values: Vec<f64> = samples.iter().filter(|(g, _)| g == name).map(|(_, v)| *v).collect();
            summarize(name, &values)
        })
        .collect::<Result<Vec<_>, _>>()?;
    let mut tests = Vec::new();
    for i in 0..groups.len() {
        for j in i + 1..groups.len() {
            tests.push(welch_from_summaries(&groups[i], &groups[j])?);
        }
    }
    Ok(GroupComparison { groups, tests })
}
