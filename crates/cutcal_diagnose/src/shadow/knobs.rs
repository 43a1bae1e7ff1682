//! The shadow's knobs (issue 10, item 1): each mechanism hook and nuisance constant with its table
//! grid, the shadow model evaluated at one knob setting (cutcal's extended Oxley model, Oxley 1989;
//! Lalwani, Mehta & Jain 2009), and the per-test tables walked outward from each knob's off value.

use cutcal_model::oxley::{OxleyOptions, OxleyPrediction};
use cutcal_model::{CuttingTest, JcParams, Material};
use rayon::prelude::*;

use super::fitted::Base;
use crate::error::DiagnoseError;
use crate::hooks::{Hook, Hooks};
use crate::simulator::oxley_with_hooks_from;
use crate::spline::Table;

/// A knob of the shadow: a mechanism hook or a nuisance constant.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Knob {
    Hook(Hook),
    /// Oxley's primary-zone temperature factor eta (Oxley 1989: 0.9).
    Eta,
    /// Oxley's interface temperature factor psi (Oxley 1989: 0.9).
    Psi,
    /// ln of a scale on rho Cp (the material's thermal constants).
    LnRhoCp,
    /// ln of a scale on the thermal conductivity K.
    LnK,
    /// ln of a scale on the JC thermal-softening exponent m.
    LnJcM,
}

/// Table grid of a knob, in the knob's coordinate (`ln` of the multiplier for the flow-stress
/// multiplier, the hook value otherwise), and its off value.
pub(super) fn grid(k: Knob) -> (Vec<f64>, f64) {
    match k {
        Knob::Hook(Hook::FrictionFactor) => ((2..=10).map(|i| f64::from(i) / 10.0).collect(), 1.0),
        Knob::Hook(Hook::HeatPartition) => (vec![0.4, 0.6, 0.8, 1.0, 1.2, 1.4, 1.6, 1.8, 2.2, 2.6, 3.0], 1.0),
        Knob::Hook(Hook::ExtraSoftening) => {
            (vec![-0.5, -0.35, -0.2, -0.1, 0.0, 0.1, 0.2, 0.35, 0.5, 0.75, 1.0, 1.25, 1.5], 0.0)
        }
        Knob::Hook(Hook::RakeShift) => {
            // Negative shifts for the edge's effective rake (down to its floor, -40 deg, less a
            // positive nominal rake), positive ones for the built-up edge.
            let deg =
                [-45.0, -36.0, -28.0, -21.0, -15.0, -10.0, -6.0, -3.0, 0.0, 2.0, 4.0, 6.0, 9.0, 12.0, 16.0, 20.0, 25.0];
            (deg.iter().map(|d: &f64| d.to_radians()).collect(), 0.0)
        }
        Knob::Hook(Hook::FlowMultiplier) => {
            (vec![-0.8, -0.6, -0.4, -0.2, 0.0, 0.2, 0.4, 0.6, 0.8, 1.0, 1.2, 1.4, 1.6, 1.8, 2.0], 0.0)
        }
        Knob::Hook(Hook::EdgeRadius) => {
            ([0.0, 5.0, 10.0, 15.0, 20.0, 30.0, 40.0, 60.0, 80.0].map(|u| u * 1e-6).to_vec(), 0.0)
        }
        Knob::Hook(Hook::WearLand) => {
            ([0.0, 0.025, 0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.4].map(|u| u * 1e-3).to_vec(), 0.0)
        }
        Knob::Eta => (vec![0.81, 0.855, 0.9, 0.945, 0.99], 0.9),
        // psi times the interface heat share: the nuisance's psi (+-3 %) and the heat-partition
        // mechanism's share of the frictional heat entering the chip (0.3-1.5) multiply here.
        Knob::Psi => (vec![0.25, 0.35, 0.45, 0.55, 0.65, 0.75, 0.81, 0.855, 0.9, 0.945, 0.99, 1.1, 1.25, 1.4], 0.9),
        Knob::LnRhoCp | Knob::LnK => (vec![-0.15, -0.075, 0.0, 0.075, 0.15], 0.0),
        // The nuisance's JC m (+-0.049) and the softening mechanism's m-scale (+-0.7) add here.
        Knob::LnJcM => (vec![-0.7, -0.5, -0.3, -0.15, -0.075, 0.0, 0.075, 0.15, 0.3, 0.5, 0.7], 0.0),
    }
}

pub(super) const KNOBS: [Knob; 12] = [
    Knob::Hook(Hook::FrictionFactor),
    Knob::Hook(Hook::HeatPartition),
    Knob::Hook(Hook::ExtraSoftening),
    Knob::Hook(Hook::RakeShift),
    Knob::Hook(Hook::FlowMultiplier),
    Knob::Hook(Hook::EdgeRadius),
    Knob::Hook(Hook::WearLand),
    Knob::Eta,
    Knob::Psi,
    Knob::LnRhoCp,
    Knob::LnK,
    Knob::LnJcM,
];

/// The shadow model for one knob setting.
pub(super) struct Shadow<'a> {
    pub(super) material: &'a Material,
    pub(super) jc: JcParams,
    /// The shadow's own tool-chip interface factor m_f (tau_int = m_f k_chip; 1 = Oxley's full
    /// sticking); the friction mechanism's factor multiplies it.
    pub(super) friction: f64,
    /// The shadow's own cutting-edge radius, m (0 = sharp; fitted behind a gate where the external
    /// simulation carries ploughing forces, e.g. an FE run with the real edge): the edge mechanism's
    /// radius adds to it.
    pub(super) edge_m: f64,
    /// The shadow's scale on Oxley's strain-rate constant C0 (1 = Oxley's normal-stress condition;
    /// fitted behind a gate where the external simulation's primary zone is not Oxley's).
    pub(super) c0_scale: f64,
}

impl<'a> Shadow<'a> {
    /// The shadow with JC set `jc` and none of its gated globals: Oxley's sticking contact, a sharp
    /// edge and Oxley's C0.
    pub(super) fn oxley(material: &'a Material, jc: JcParams) -> Self {
        Self { material, jc, friction: 1.0, edge_m: 0.0, c0_scale: 1.0 }
    }

    /// The shadow's `ln Fc, ln Ft, ln t2, T_AB, T_int` at test `t` with one knob set, warm-started
    /// at a nearby solution; also returns the solution.
    pub(super) fn eval_from(
        &self,
        t: &CuttingTest,
        knob: Option<(Knob, f64)>,
        start: Option<&OxleyPrediction>,
    ) -> Result<([f64; 5], OxleyPrediction), DiagnoseError> {
        let mut h = Hooks {
            friction_factor: self.friction,
            edge_radius_m: self.edge_m,
            c0_scale: self.c0_scale,
            ..Hooks::NEUTRAL
        };
        let mut options = OxleyOptions::wide();
        let mut scaled: Material;
        let mut material = self.material;
        let mut jc = self.jc;
        match knob {
            Some((Knob::Hook(Hook::FlowMultiplier), u)) => h.flow_multiplier = u.exp(),
            Some((Knob::Hook(Hook::FrictionFactor), u)) => h.friction_factor = self.friction * u,
            Some((Knob::Hook(Hook::EdgeRadius), u)) => h.edge_radius_m = self.edge_m + u,
            Some((Knob::Hook(k), u)) => h = k.with(h, u),
            Some((Knob::Eta, u)) => options.eta = u,
            // Oxley's psi and the interface heat share both scale dT_M; the share carries the
            // product so that it may exceed psi's own bound of 1.
            Some((Knob::Psi, u)) => h.interface_heat_share = u / options.psi,
            Some((Knob::LnRhoCp, u)) => {
                scaled = self.material.clone();
                scaled.thermal.rho_cp = scaled.thermal.rho_cp.scaled(u.exp());
                material = &scaled;
            }
            Some((Knob::LnK, u)) => {
                scaled = self.material.clone();
                scaled.thermal.conductivity = scaled.thermal.conductivity.scaled(u.exp());
                material = &scaled;
            }
            Some((Knob::LnJcM, u)) => jc.m *= u.exp(),
            None => {}
        }
        let (p, full) = oxley_with_hooks_from(material, &jc, t, &h, &options, start)?;
        let y =
            [p.fc_n_per_m.ln(), p.ft_n_per_m.ln(), p.chip_m.ln(), p.t_ab_c.unwrap_or(0.0), p.t_int_c.unwrap_or(0.0)];
        if y.iter().all(|v| v.is_finite()) {
            Ok((y, full))
        } else {
            // A non-positive force (a feed force can change sign at large rake) has no log-signature.
            Err(DiagnoseError::Inconsistent(format!(
                "test {}: the shadow gives a non-positive force or chip (Fc {:.1}, Ft {:.1} N/mm)",
                t.id,
                p.fc_n_per_m / 1e3,
                p.ft_n_per_m / 1e3
            )))
        }
    }
}

/// The shadow's tables at every test it solves ([`knob_table`] for each knob).
pub(super) fn tables_at(
    sh: &Shadow<'_>,
    tests: &[CuttingTest],
    bases: &[Option<Base>],
) -> Vec<Option<Result<Vec<Table>, DiagnoseError>>> {
    tests
        .par_iter()
        .zip(bases)
        .map(|(t, b)| b.as_ref().map(|b| KNOBS.iter().map(|&k| knob_table(sh, t, k, b)).collect()))
        .collect()
}

/// Knob `k`'s table at test `t`, walked outward from the off node (the test's `base`, the shadow at
/// the knobs' off values), each node warm-started at its neighbour; the walk stops at the first
/// node without a solution.
fn knob_table(sh: &Shadow<'_>, t: &CuttingTest, k: Knob, &(base, base_sol): &Base) -> Result<Table, DiagnoseError> {
    let (nodes, off) = grid(k);
    let k0 = nodes.iter().position(|u| (u - off).abs() < 1e-12).unwrap_or(0);
    let mut values: Vec<Option<[f64; 5]>> = vec![None; nodes.len()];
    values[k0] = Some(base);
    for dir in [1i64, -1] {
        let mut prev = Some(base_sol);
        let mut i = k0 as i64 + dir;
        while i >= 0 && (i as usize) < nodes.len() {
            match sh.eval_from(t, Some((k, nodes[i as usize])), prev.as_ref()) {
                Ok((y, sol)) => {
                    values[i as usize] = Some(y);
                    prev = Some(sol);
                }
                Err(_) => break,
            }
            i += dir;
        }
    }
    Table::new(&nodes, &values, off)
}
