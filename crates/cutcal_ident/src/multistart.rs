//! Seeded, deterministic multistart around the bounded LM solver, and fit statistics
//! (covariance and correlation of the free parameters from the Jacobian).
//!
//! **Basin rule (optional, [`BasinStop`]).** A start whose iterate comes within a radius `rho`
//! (Euclidean, in unit-box coordinates) of a minimum already found by a converged start, with an
//! SSR not below that minimum's, is stopped and counted as having joined it. This is the distance
//! filter of Ugray et al. (INFORMS J. Computing 19 (2007) 328-340, Sec 3: a point inside the
//! "basin radius" of a found local solution and not better than it starts no local solve), the
//! critical-distance rule of multi-level single linkage (Rinnooy Kan and Timmer, Math. Programming
//! 39 (1987) 57-78) applied to the iterates of a running solve instead of to sample points only.
//! Stopped starts are reported ([`MultistartReport::stopped_starts`]) and never become the best;
//! the first start always runs to convergence.
//!
//! **Sample filter (optional, [`SampleFilter`], [`crate::start_filter`]).** Multi-level single
//! linkage: a local search starts only from sample points with no better sample point within the
//! critical distance. Start 0 (the centre, or the caller's warm start) is always searched. Sample
//! points not searched are reported ([`MultistartReport::filtered_starts`]); they never count as
//! having reached a minimum.
//!
//! The fit statistics of a solution are in [`crate::fit_stats`].

use nalgebra::DVector;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use crate::error::IdentError;
pub use crate::fit_stats::{fit_statistics, FitStatistics};
use crate::lm::{minimise, minimise_until, Bounds, LmOptions, LmResult, Problem, Termination};
use crate::start_filter::{distance, mlsl_filter};
pub use crate::start_filter::{mlsl_critical_distance, SampleFilter, MLSL_SIGMA};

/// Multistart settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MultistartOptions {
    /// Number of starts (>= 1). Start 0 is the centre of the box; the others a Latin hypercube.
    pub starts: usize,
    /// Seed of the ChaCha8 generator of the Latin hypercube.
    pub seed: u64,
    /// Local solver settings.
    pub lm: LmOptions,
    /// Two minima are "the same" when their SSR differ by less than this relative amount.
    pub same_minimum_rel_tol: f64,
    /// Whether starts are stopped on entering a found minimum's basin (see the module).
    pub basin_stop: BasinStop,
    /// Whether sample points are filtered by MLSL's critical distance before any local search
    /// (see the module).
    pub sample_filter: SampleFilter,
}

impl MultistartOptions {
    /// `starts` starts from `seed` with precise local solves and the caller's default basin rule.
    #[must_use]
    pub fn new(starts: usize, seed: u64) -> Self {
        Self {
            starts,
            seed,
            lm: LmOptions::precise(),
            same_minimum_rel_tol: 1e-6,
            basin_stop: BasinStop::Auto,
            sample_filter: SampleFilter::Auto,
        }
    }
}

/// The basin rule of the multistart (module docs).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum BasinStop {
    /// The caller's default: off in the generic [`multistart`] (every start runs to convergence),
    /// [`DPZD_BASIN_RADIUS`] in the DPZD identification ([`crate::dpzd_fit::identify`]).
    Auto,
    /// Every start runs to convergence.
    Off,
    /// Stop at this unit-box radius (0 < radius <= 1).
    Radius(f64),
}

impl BasinStop {
    /// The radius this rule applies, given the caller's default for [`BasinStop::Auto`].
    #[must_use]
    pub fn radius(self, auto: Option<f64>) -> Option<f64> {
        match self {
            Self::Auto => auto,
            Self::Off => None,
            Self::Radius(r) => Some(r),
        }
    }
}

/// Basin radius of the DPZD identification (unit box of `(n, C, m)`).
///
/// 0.1, a quarter of the MLSL critical distance at 50 points ([`mlsl_critical_distance`] with
/// [`MLSL_SIGMA`]: 0.34): a search is only stopped once it is already close to a found minimum and
/// not below it. It was 0.05 before the MLSL filter; at 0.1 the 50-start identification of C38
/// test 3 needs 14 % fewer instructions, and the property tests of `tests/varpro.rs` (every start
/// searched against the full 5-parameter LM; the filtered multistart against the exhaustive one)
/// pass on 3000 cases each (`CUTCAL_FUZZ_CASES=3000`).
pub const DPZD_BASIN_RADIUS: f64 = 0.1;

/// The outcome of a multistart run.
#[derive(Debug, Clone, PartialEq)]
pub struct MultistartReport {
    /// The best local solution.
    pub best: LmResult,
    /// Which start gave it (0-based).
    pub best_start: usize,
    /// Starts run.
    pub starts: usize,
    /// Starts whose solve failed.
    pub failed_starts: usize,
    /// Starts that reached the best minimum (within `same_minimum_rel_tol`).
    pub starts_at_best: usize,
    /// SSR reached from each start (`None` where it failed or was filtered; for a stopped start,
    /// the SSR of the minimum it joined).
    pub start_ssr: Vec<Option<f64>>,
    /// Sample points from which no local search was started, because a sample point with a lower
    /// objective lay within the MLSL critical distance (never counted in `starts_at_best`).
    pub filtered_starts: usize,
    /// The MLSL critical distance applied (unit box; `None`: no filter).
    pub critical_distance: Option<f64>,
    /// Starts stopped by the basin rule (counted in `starts_at_best` when they joined the best).
    pub stopped_starts: usize,
    /// Of those, the starts that joined the best minimum.
    pub stopped_at_best: usize,
    /// For each start, the start whose minimum it joined when the basin rule stopped it.
    pub joined: Vec<Option<usize>>,
    /// Starts that stopped at the LM iteration cap without meeting a tolerance. They are not
    /// chosen as the best while any start converged; when none did, `best.termination` is
    /// [`Termination::MaxIterations`] and callers must report it (a typed non-convergence).
    pub unconverged_starts: usize,
}

/// The start points in unit-box coordinates: the centre, then a Latin hypercube of `starts - 1`.
#[must_use]
pub fn start_points(dim: usize, starts: usize, seed: u64) -> Vec<DVector<f64>> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut pts = vec![DVector::from_element(dim, 0.5)];
    let k = starts.saturating_sub(1);
    if k == 0 {
        return pts;
    }
    let mut columns: Vec<Vec<f64>> = Vec::with_capacity(dim);
    for _ in 0..dim {
        let mut strata: Vec<f64> = (0..k).map(|i| (i as f64 + rng.gen::<f64>()) / k as f64).collect();
        // Fisher-Yates with the same generator: deterministic for a seed.
        for i in (1..k).rev() {
            let j = rng.gen_range(0..=i);
            strata.swap(i, j);
        }
        columns.push(strata);
    }
    for s in 0..k {
        pts.push(DVector::from_iterator(dim, columns.iter().map(|c| c[s])));
    }
    pts
}

/// Runs the bounded LM from every start and keeps the best.
///
/// With [`BasinStop::Radius`] (here `Auto` is off) starts are stopped by the basin rule.
///
/// Returns an error if the options are invalid or every start fails.
pub fn multistart<P: Problem + ?Sized>(
    problem: &P,
    bounds: &Bounds,
    options: &MultistartOptions,
) -> Result<MultistartReport, IdentError> {
    multistart_with_basin(problem, bounds, options, options.basin_stop.radius(None))
}

/// [`multistart`] with an explicit basin radius (`None`: every start runs to convergence).
///
/// Returns an error as [`multistart`], or if the radius is not in `(0, 1]`.
pub fn multistart_with_basin<P: Problem + ?Sized>(
    problem: &P,
    bounds: &Bounds,
    options: &MultistartOptions,
    basin_radius: Option<f64>,
) -> Result<MultistartReport, IdentError> {
    multistart_from(problem, bounds, options, basin_radius, options.sample_filter.sigma(None), None)
}

/// [`multistart_with_basin`] with start 0 at `first` (physical parameters, clamped into the box)
/// instead of the centre of the box: a warm start (e.g. a Monte-Carlo sample started from the
/// nominal solution). The other starts are the same Latin hypercube. With `mlsl_sigma` the sample
/// points are filtered by MLSL's critical distance before any local search (module docs).
///
/// Returns an error as [`multistart_with_basin`], if `first` has the wrong length, or if
/// `mlsl_sigma` is not positive and finite.
pub fn multistart_from<P: Problem + ?Sized>(
    problem: &P,
    bounds: &Bounds,
    options: &MultistartOptions,
    basin_radius: Option<f64>,
    mlsl_sigma: Option<f64>,
    first: Option<&DVector<f64>>,
) -> Result<MultistartReport, IdentError> {
    if first.is_some_and(|f| f.len() != bounds.len()) {
        return Err(IdentError::InvalidOptions(format!(
            "the warm start has {} parameters, the bounds {}",
            first.map_or(0, DVector::len),
            bounds.len()
        )));
    }
    if options.starts == 0 || options.starts > 100_000 {
        return Err(IdentError::InvalidOptions(format!("starts must be in 1..=100000, got {}", options.starts)));
    }
    if let Some(r) = basin_radius {
        if !(r > 0.0 && r <= 1.0) {
            return Err(IdentError::InvalidOptions(format!("the basin radius must be in (0, 1], got {r}")));
        }
    }
    if let Some(s) = mlsl_sigma {
        if !(s > 0.0 && s.is_finite()) {
            return Err(IdentError::InvalidOptions(format!("the MLSL sigma must be positive and finite, got {s}")));
        }
    }
    let units: Vec<DVector<f64>> = start_points(bounds.len(), options.starts, options.seed)
        .into_iter()
        .enumerate()
        .map(|(i, z0)| match first {
            Some(f) if i == 0 => bounds.to_unit(f),
            _ => z0,
        })
        .collect();
    let free_dims = (0..bounds.len()).filter(|&i| bounds.upper[i] > bounds.lower[i]).count();
    let critical_distance =
        mlsl_sigma.map(|s| mlsl_critical_distance(free_dims, options.starts, s)).filter(|r| *r > 0.0);
    let filtered = match critical_distance {
        Some(rk) => mlsl_filter(problem, bounds, &units, rk),
        None => vec![false; units.len()],
    };
    // The best converged start, and the best of all (used only when no start converged).
    let mut best: Option<(usize, LmResult)> = None;
    let mut best_capped: Option<(usize, LmResult)> = None;
    let mut unconverged_starts = 0;
    let mut start_ssr = Vec::with_capacity(options.starts);
    let mut joined = vec![None; options.starts];
    // Minima found by converged starts: (unit-box point, SSR, start index).
    let mut minima: Vec<(DVector<f64>, f64, usize)> = Vec::new();
    let mut first_error = None;
    for (i, z0) in units.iter().enumerate() {
        if filtered[i] {
            start_ssr.push(None);
            continue;
        }
        let p0 = bounds.from_unit(z0);
        let mut hit = None;
        let outcome = match basin_radius {
            Some(rho) if !minima.is_empty() => minimise_until(problem, bounds, &p0, &options.lm, |z, ssr| {
                hit = minima.iter().position(|(zm, sm, _)| ssr >= *sm && distance(z, zm) <= rho);
                hit.is_some()
            }),
            _ => minimise(problem, bounds, &p0, &options.lm),
        };
        match outcome {
            Ok(res) if res.termination == Termination::Stopped => {
                let (_, ssr, owner) = hit.map(|k| minima[k].clone()).expect("a stopped start names its minimum");
                start_ssr.push(Some(ssr));
                joined[i] = Some(owner);
            }
            Ok(res) => {
                start_ssr.push(Some(res.ssr));
                let slot = if res.termination == Termination::MaxIterations {
                    unconverged_starts += 1;
                    &mut best_capped
                } else {
                    if basin_radius.is_some() {
                        minima.push((bounds.to_unit(&res.params), res.ssr, i));
                    }
                    &mut best
                };
                if slot.as_ref().is_none_or(|(_, b)| res.ssr < b.ssr) {
                    *slot = Some((i, res));
                }
            }
            Err(e) => {
                start_ssr.push(None);
                first_error.get_or_insert(e.to_string());
            }
        }
    }
    let (best_start, best) = best.or(best_capped).ok_or_else(|| IdentError::AllStartsFailed {
        starts: options.starts,
        first: first_error.clone().unwrap_or_default(),
    })?;
    let tol = options.same_minimum_rel_tol * best.ssr.max(f64::MIN_POSITIVE) + 1e-300;
    let at_best = |s: &f64| (*s - best.ssr).abs() <= tol;
    let starts_at_best = start_ssr.iter().flatten().filter(|s| at_best(s)).count();
    let stopped_starts = joined.iter().flatten().count();
    let stopped_at_best =
        joined.iter().zip(&start_ssr).filter(|(j, s)| j.is_some() && s.as_ref().is_some_and(at_best)).count();
    let filtered_starts = filtered.iter().filter(|f| **f).count();
    let failed_starts = start_ssr.iter().filter(|s| s.is_none()).count() - filtered_starts;
    Ok(MultistartReport {
        best,
        best_start,
        starts: options.starts,
        failed_starts,
        starts_at_best,
        start_ssr,
        stopped_starts,
        stopped_at_best,
        joined,
        unconverged_starts,
        filtered_starts,
        critical_distance,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::lm::tests::Rosen;

    #[test]
    fn capped_starts_are_counted_and_never_preferred_to_a_converged_one() {
        let b = Bounds::new(vec!["x".into(), "y".into()], vec![-2.0, -1.0], vec![2.0, 3.0]).unwrap();
        // A cap of 12 iterations: with seed 5, 3 of 9 starts stop at the cap and 6 converge.
        let mut o = MultistartOptions::new(9, 5);
        o.lm.max_iterations = 12;
        let r = multistart(&Rosen, &b, &o).unwrap();
        println!("unconverged {} of 9, best {:?}", r.unconverged_starts, r.best.termination);
        assert!(r.unconverged_starts > 0 && r.unconverged_starts < 9, "{}", r.unconverged_starts);
        assert_ne!(r.best.termination, Termination::MaxIterations);
        // A cap of 1: no start converges; the best says MaxIterations for the caller to report.
        o.lm.max_iterations = 1;
        let r = multistart(&Rosen, &b, &o).unwrap();
        assert_eq!(r.unconverged_starts, 9);
        assert_eq!(r.best.termination, Termination::MaxIterations);
    }

    /// `r = (x^2 - 1, 0.3 (x - 1), 0.5)`: the global minimum x = 1 (SSR 0.25) and a local one
    /// near x = -1 (SSR about 0.61), separated by a maximum near 0.
    struct TwoMinima;
    impl Problem for TwoMinima {
        fn parameter_count(&self) -> usize {
            1
        }
        fn residual_count(&self) -> usize {
            3
        }
        fn residuals(&self, p: &DVector<f64>, out: &mut DVector<f64>) -> Result<(), IdentError> {
            out[0] = p[0] * p[0] - 1.0;
            out[1] = 0.3 * (p[0] - 1.0);
            out[2] = 0.5;
            Ok(())
        }
    }

    #[test]
    fn basin_rule_stops_starts_in_both_basins_and_keeps_the_counts() {
        let b = Bounds::new(vec!["x".into()], vec![-2.0], vec![2.0]).unwrap();
        let o = MultistartOptions::new(20, 4);
        let all = multistart(&TwoMinima, &b, &o).unwrap();
        assert_eq!(o.basin_stop, BasinStop::Auto);
        assert_eq!(all.stopped_starts, 0, "Auto is off in the generic multistart");
        let fast = multistart_with_basin(&TwoMinima, &b, &o, Some(0.1)).unwrap();
        println!(
            "all: at best {}; fast: at best {}, stopped {} ({} at best)",
            all.starts_at_best, fast.starts_at_best, fast.stopped_starts, fast.stopped_at_best
        );
        // The same best minimum and the same count of starts at it; both basins had stopped starts.
        assert!((fast.best.params[0] - 1.0).abs() < 1e-6 && (all.best.params[0] - 1.0).abs() < 1e-6);
        assert_eq!(fast.starts_at_best, all.starts_at_best);
        assert!(all.starts_at_best < 20, "some starts must reach the local minimum");
        assert!(fast.stopped_at_best > 0 && fast.stopped_starts > fast.stopped_at_best, "{fast:?}");
        // A stopped start names a converged start that found its minimum.
        for (i, j) in fast.joined.iter().enumerate() {
            if let Some(j) = j {
                assert!(*j < i && fast.joined[*j].is_none());
            }
        }
        assert!(multistart_with_basin(&TwoMinima, &b, &o, Some(0.0)).is_err());
        assert!(multistart_with_basin(&TwoMinima, &b, &o, Some(f64::NAN)).is_err());
    }

    #[test]
    fn start_points_are_a_latin_hypercube_and_deterministic() {
        let a = start_points(3, 11, 7);
        let b = start_points(3, 11, 7);
        assert_eq!(a, b);
        assert_eq!(a.len(), 11);
        // Each of the 10 strata of every coordinate holds exactly one point.
        for d in 0..3 {
            let mut hit = [0usize; 10];
            for p in &a[1..] {
                hit[(p[d] * 10.0).floor() as usize] += 1;
            }
            assert!(hit.iter().all(|h| *h == 1), "{hit:?}");
        }
        assert_ne!(start_points(3, 11, 8), a);
    }
}
