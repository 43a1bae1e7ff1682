//! What the data determine: the singular values of the noise-weighted Jacobian, scaled by the
//! width of each parameter's plausibility box.
//!
//! Scaling: column k of the Jacobian is multiplied by the width `w_k` of parameter k's box, and row
//! i is divided by the measurement's standard deviation `sigma_i` (same units as the residual). In
//! these units a singular value `s_j` says how many standard deviations of the data a move along
//! the j-th right singular direction by one full box width produces. To first order the 1-sd
//! uncertainty along that direction is `1/s_j` box widths (Gauss-Newton covariance, e.g. Bates &
//! Watts 1988, Sec. 2.3).
//!
//! A direction is **determined** when that uncertainty is below [`DETERMINED_FRACTION`] of the box
//! width, i.e. the data narrow it by at least a factor 4 beyond what the literature box already
//! says. The **effective rank** is the number of determined directions, and a set is determined
//! when every free parameter's direction is. The condition number `s_max/s_min` is reported beside
//! it. Fixed parameters (zero-width box) are left out.

use nalgebra::DMatrix;
use serde::Serialize;

/// 1-sd uncertainty, as a fraction of the box width, below which a direction counts as determined.
pub const DETERMINED_FRACTION: f64 = 0.25;

/// What the data determine at a solution.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Identifiability {
    /// The free parameters (box width > 0), in column order.
    pub parameters: Vec<String>,
    /// Singular values of the scaled Jacobian, largest first.
    pub singular_values: Vec<f64>,
    /// `s_max / s_min`; `None` when the smallest singular value is 0.
    pub condition_number: Option<f64>,
    /// Number of directions determined to better than [`DETERMINED_FRACTION`] of the box.
    pub effective_rank: usize,
    /// Whether every free direction is determined.
    pub determined: bool,
    /// The least determined direction: each parameter's component of the right singular vector of
    /// the smallest singular value (largest magnitude first).
    pub weakest_direction: Vec<(String, f64)>,
    /// The 1-sd uncertainty along the weakest direction in box widths; `None` if unbounded.
    pub weakest_uncertainty_in_box_widths: Option<f64>,
}

/// Assesses a Jacobian `jac` (residuals x parameters) with residual standard deviations `sd`
/// (one per row) and box widths `widths` (one per column).
///
/// Returns `None` when nothing is free, the shapes disagree, or an entry is not finite.
#[must_use]
pub fn assess(jac: &DMatrix<f64>, sd: &[f64], widths: &[f64], names: &[String]) -> Option<Identifiability> {
    let (m, p) = jac.shape();
    if sd.len() != m || widths.len() != p || names.len() != p || m == 0 {
        return None;
    }
    let free: Vec<usize> = (0..p).filter(|&k| widths[k] > 0.0).collect();
    if free.is_empty() || sd.iter().any(|s| !(s.is_finite() && *s > 0.0)) {
        return None;
    }
    let scaled = DMatrix::from_fn(m, free.len(), |i, k| jac[(i, free[k])] * widths[free[k]] / sd[i]);
    if scaled.iter().any(|v| !v.is_finite()) {
        return None;
    }
    // With fewer rows than columns pad with zero rows so that every column has a singular value.
    let rows = m.max(free.len());
    let padded = DMatrix::from_fn(rows, free.len(), |i, k| if i < m { scaled[(i, k)] } else { 0.0 });
    let svd = padded.svd(false, true);
    let v_t = svd.v_t?;
    let mut order: Vec<usize> = (0..free.len()).collect();
    order.sort_by(|&a, &b| svd.singular_values[b].total_cmp(&svd.singular_values[a]));
    let sv: Vec<f64> = order.iter().map(|&j| svd.singular_values[j]).collect();
    let smallest = *order.last()?;
    let s_min = svd.singular_values[smallest];
    let effective_rank = sv.iter().filter(|&&s| s > 0.0 && 1.0 / s < DETERMINED_FRACTION).count();
    let mut weakest: Vec<(String, f64)> =
        free.iter().enumerate().map(|(k, &c)| (names[c].clone(), v_t[(smallest, k)])).collect();
    weakest.sort_by(|a, b| b.1.abs().total_cmp(&a.1.abs()));
    Some(Identifiability {
        parameters: free.iter().map(|&c| names[c].clone()).collect(),
        condition_number: (s_min > 0.0).then(|| sv[0] / s_min),
        determined: effective_rank == free.len(),
        effective_rank,
        weakest_uncertainty_in_box_widths: (s_min > 0.0).then(|| 1.0 / s_min),
        weakest_direction: weakest,
        singular_values: sv,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(n: usize) -> Vec<String> {
        (0..n).map(|i| format!("p{i}")).collect()
    }

    #[test]
    fn a_diagonal_jacobian_has_its_scaled_entries_as_singular_values() {
        // J = diag(2, 0.5), sd 0.1, widths 1 and 2: scaled diag(20, 10) -> rank 2, cond 2.
        let j = DMatrix::from_row_slice(2, 2, &[2.0, 0.0, 0.0, 0.5]);
        let a = assess(&j, &[0.1, 0.1], &[1.0, 2.0], &names(2)).unwrap();
        assert!((a.singular_values[0] - 20.0).abs() < 1e-12 && (a.singular_values[1] - 10.0).abs() < 1e-12);
        assert_eq!(a.effective_rank, 2);
        assert!(a.determined);
        assert!((a.condition_number.unwrap() - 2.0).abs() < 1e-12);
        assert_eq!(a.weakest_direction[0].0, "p1");
    }

    #[test]
    fn two_parameters_that_act_only_through_their_sum_are_not_both_determined() {
        // r = p0 + p1 at three points: J has two equal columns, rank 1; the weakest direction is
        // p0 - p1 (components +-1/sqrt 2).
        let j = DMatrix::from_row_slice(3, 2, &[1.0, 1.0, 2.0, 2.0, 3.0, 3.0]);
        let a = assess(&j, &[0.01; 3], &[1.0, 1.0], &names(2)).unwrap();
        assert_eq!(a.effective_rank, 1);
        assert!(!a.determined);
        assert!(a.condition_number.is_none() || a.condition_number.unwrap() > 1e12);
        let w = &a.weakest_direction;
        assert!((w[0].1.abs() - 0.5f64.sqrt()).abs() < 1e-9 && (w[0].1 + w[1].1).abs() < 1e-9);
    }

    #[test]
    fn noise_decides_between_determined_and_not() {
        // One parameter, sensitivity 1 per box width: sd 0.2 gives 1-sd uncertainty 0.2 box widths
        // (determined), sd 0.3 gives 0.3 (not determined).
        let j = DMatrix::from_row_slice(1, 1, &[1.0]);
        assert!(assess(&j, &[0.2], &[1.0], &names(1)).unwrap().determined);
        assert!(!assess(&j, &[0.3], &[1.0], &names(1)).unwrap().determined);
    }

    #[test]
    fn fixed_parameters_are_left_out_and_fewer_rows_than_columns_work() {
        let j = DMatrix::from_row_slice(1, 3, &[1.0, 5.0, 2.0]);
        let a = assess(&j, &[0.01], &[1.0, 0.0, 1.0], &names(3)).unwrap();
        assert_eq!(a.parameters, vec!["p0".to_string(), "p2".to_string()]);
        assert_eq!(a.effective_rank, 1);
        assert!(!a.determined);
    }
}
