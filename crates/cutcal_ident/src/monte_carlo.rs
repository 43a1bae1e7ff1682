//! The per-sample identification of the Monte-Carlo propagation ([`crate::bootstrap`]),
//! warm-started from the nominal fit.
//!
//! A sample differs from the nominal test by a few percent in the measurements and by the drawn
//! unstated choices (h factor, r offset), so its minimum lies near the nominal one. Each sample
//! therefore solves its own DPZD zone (the one forward model, [`cutcal_model::dpzd`]) and runs a
//! short multistart whose first start is the nominal solution ([`MultistartOptions::starts`] in
//! all; the basin rule of [`crate::multistart`] stops the others once they join a found minimum):
//!
//! - `paper` objective: [`crate::dpzd_fit::identify_warm`] on the N uniform points;
//! - `converged` objective: [`crate::quadrature::identify_converged_warm`], whose first
//!   quadrature rule is refined from the nominal rule's panels instead of from the two halves.
//!
//! `tests/fast_path.rs` shows on seeded C38 test 3 draws that this finds the minimum of the cold
//! full multistart (`cutcal identify`'s own path) to a stated tolerance.
//!
//! The zone thickness of a sample is the nominal h times the drawn factor (the h range is one of
//! the unstated choices); it is not re-solved through the Oxley model per sample.

use cutcal_model::dpzd::{self, DpzdConfig, ShearPlaneState, ZoneSolution};
use cutcal_model::{CuttingTest, JcParams, Material, RateTerm};
use nalgebra::DVector;

use crate::bootstrap::Sample;
use crate::dpzd_fit::{identify_warm_with, JcBounds, JcConstants, JcIdentification, ZoneFitProblem};
use crate::error::IdentError;
use crate::multistart::MultistartOptions;
use crate::quadrature::{identify_converged_warm_with, ConvergedOptions, WarmStart};

/// The Eq 15 objective a sample is identified with (the nominal identification's).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SampleObjective {
    /// The discrete sum at `points` uniform interior points with the given rate term (`paper`
    /// preset: 51 points, unclamped).
    Uniform {
        /// Interior points (>= 6).
        points: usize,
        /// Rate term of the law.
        rate_term: RateTerm,
    },
    /// The zone integral with the clamped law (`converged` preset).
    Converged(ConvergedOptions),
}

/// Identifies Monte-Carlo samples of one test, warm-started from its nominal identification.
#[derive(Debug, Clone)]
pub struct WarmSampleIdentifier<'a> {
    material: &'a Material,
    test: &'a CuttingTest,
    config: DpzdConfig,
    bounds: JcBounds,
    constants: JcConstants,
    objective: SampleObjective,
    multistart: MultistartOptions,
    nominal: DVector<f64>,
    warm: Option<WarmStart>,
}

impl<'a> WarmSampleIdentifier<'a> {
    /// The identifier of `test`'s samples: `config` is the nominal DPZD configuration (h and r
    /// before the sample's factor and offset), `nominal_zone` and `nominal` the nominal zone and
    /// its identification with `objective`, `multistart` the per-sample starts (the first is the
    /// nominal solution).
    ///
    /// Returns an error if the bounds are invalid or the nominal rule cannot be rebuilt.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        material: &'a Material,
        test: &'a CuttingTest,
        config: DpzdConfig,
        bounds: JcBounds,
        constants: JcConstants,
        objective: SampleObjective,
        multistart: MultistartOptions,
        nominal_zone: &ZoneSolution,
        nominal: &JcIdentification,
    ) -> Result<Self, IdentError> {
        bounds.to_bounds()?;
        if let SampleObjective::Uniform { points, .. } = objective {
            if points < 6 {
                return Err(IdentError::InvalidOptions(format!("at least 6 fit points are needed, got {points}")));
            }
        }
        let warm = match objective {
            SampleObjective::Converged(o) => {
                Some(WarmStart::from_identification(nominal_zone, nominal, constants, &o)?)
            }
            SampleObjective::Uniform { .. } => None,
        };
        let jc = &nominal.jc;
        let nominal = DVector::from_vec(vec![jc.a_pa / 1e6, jc.b_pa / 1e6, jc.n, jc.c, jc.m]);
        Ok(Self { material, test, config, bounds, constants, objective, multistart, nominal, warm })
    }

    /// The DPZD zone of a sample: its measurement, h times its factor and r plus its offset.
    ///
    /// Returns an error if the perturbed test or configuration is invalid or the zone has no
    /// solution.
    pub fn zone(&self, s: &Sample) -> Result<ZoneSolution, IdentError> {
        let m = &s.measurement;
        let t = self
            .test
            .clone()
            .with_forces(Some(m.cutting_force_n_per_m), Some(m.feed_force_n_per_m))?
            .with_chip_thickness(Some(m.chip_thickness_m))?;
        let config = DpzdConfig::new(
            self.config.zone_thickness_m * s.h_factor,
            self.config.r + s.r_offset,
            self.config.variant,
        )?;
        Ok(dpzd::solve(self.material, &ShearPlaneState::from_test(&t)?, &config)?)
    }

    /// The identified set of a sample (the closure [`crate::bootstrap::bootstrap`] takes).
    ///
    /// **Source:** paper Eq 15 (objective as the nominal identification's).
    ///
    /// Returns an error if the zone or the identification fails.
    pub fn identify(&self, s: &Sample) -> Result<JcParams, IdentError> {
        let zone = self.zone(s)?;
        match (self.objective, &self.warm) {
            (SampleObjective::Uniform { points, rate_term }, _) => {
                let pts = zone.interior_points(points)?;
                let w = vec![1.0; pts.len()];
                let problem = ZoneFitProblem::weighted(pts, &w, self.constants, rate_term);
                Ok(identify_warm_with(&problem, &self.bounds, &self.multistart, Some(&self.nominal), false)?.jc)
            }
            (SampleObjective::Converged(o), Some(warm)) => Ok(identify_converged_warm_with(
                &zone,
                &self.bounds,
                self.constants,
                &self.multistart,
                &o,
                warm,
                false,
            )?
            .identification
            .jc),
            (SampleObjective::Converged(_), None) => {
                Err(IdentError::InvalidOptions("the converged objective needs the nominal rule".into()))
            }
        }
    }
}
