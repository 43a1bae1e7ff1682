//! The per-dataset context a mechanism needs, computed from the tests only: the wear state (from
//! measured VB, the `order` column or the row order), the built-up-edge onset, the reference speed
//! of the friction law, the reference thickness of the size effect and the recorded edge shape
//! (design note `discrepancy-discovery.md` Sec 2.2, mechanisms M1, M3, M5, M9, M10).

use cutcal_model::CuttingTest;

use crate::hooks::Hooks;
use crate::simulator::Simulator;

/// Per-dataset context a mechanism needs (computed from the tests only).
#[derive(Debug, Clone, PartialEq)]
pub struct Context {
    /// Wear state per test in [0, 1]: VB/VB_max when VB was measured, else order/order_max.
    pub wear_state: Option<Vec<f64>>,
    /// Built-up-edge onset on the gate coordinate (chosen on a grid by the fitter): the interface
    /// temperature, degC, when `bue_gate_c` is set, else the speed, m/min.
    pub bue_onset: f64,
    /// The baseline's tool-chip interface temperature per test, degC, when the simulator gives it at
    /// every test: the built-up edge is then gated by it (it forms on a cool interface and
    /// disappears as the interface heats, Trent & Wright 2000), else by the speed.
    pub bue_gate_c: Option<Vec<f64>>,
    /// Reference speed of the speed-dependent friction factor, m/min: the geometric mean of the
    /// test speeds of the whole dataset (kept in folds, so that m_f0 means the same in each).
    pub friction_v_ref_m_min: f64,
    /// Reference uncut chip thickness of the size effect, m: the geometric mean of the test
    /// thicknesses of the whole dataset (kept in folds). The simulation's flow stress was set for
    /// the thicknesses it is used at, so a size effect is the change relative to them; the common
    /// level is the baseline's, bounded by the JC uncertainty (`crate::nuisance`).
    pub size_h_ref_m: f64,
    /// Recorded edge radius per test over the mean recorded radius, when every test records one.
    pub edge_shape: Option<Vec<f64>>,
    /// Whether the run order behind `wear_state` is the row order of the recordings (no `order`
    /// and no `flank_wear_mm` column): the report says so.
    pub order_from_rows: bool,
}

impl Context {
    /// The context of a set of tests (wear state from VB, else from the test order, else from the
    /// row order: test logs are kept in the order the tests were run, and the report says when
    /// this assumption was made). Rows sorted by uncut chip thickness or by speed are a sorted
    /// listing, not a run log, and a trend over them could not be told from that variable's own
    /// effect: then no run order is assumed.
    #[must_use]
    pub fn of(tests: &[CuttingTest]) -> Self {
        let vb: Vec<Option<f64>> = tests.iter().map(|t| t.flank_wear_m).collect();
        let mut order_from_rows = false;
        let wear_state = if vb.iter().all(Option::is_some) {
            let max = vb.iter().flatten().fold(0.0f64, |a, b| a.max(*b));
            (max > 0.0).then(|| vb.iter().flatten().map(|v| v / max).collect())
        } else if tests.iter().all(|t| t.order.is_some()) {
            let max = tests.iter().filter_map(|t| t.order).max().unwrap_or(0) as f64;
            (max > 0.0).then(|| tests.iter().filter_map(|t| t.order).map(|o| o as f64 / max).collect())
        } else if tests.len() >= 2
            && tests.iter().all(|t| t.order.is_none())
            && !sorted_by(tests, |t| t.uncut_chip_thickness_m)
            && !sorted_by(tests, |t| t.speed_m_per_s)
        {
            // Row i of n ran i-th: state (i + 1) / n, as an `order` column 1..n would give.
            order_from_rows = true;
            let n = tests.len() as f64;
            Some((0..tests.len()).map(|i| (i + 1) as f64 / n).collect())
        } else {
            None
        };
        let ln_v: f64 = tests.iter().map(|t| (t.speed_m_per_s * 60.0).ln()).sum::<f64>();
        let friction_v_ref_m_min = if tests.is_empty() { 1.0 } else { (ln_v / tests.len() as f64).exp() };
        let ln_h: f64 = tests.iter().map(|t| t.uncut_chip_thickness_m.max(1e-9).ln()).sum::<f64>();
        let size_h_ref_m = if tests.is_empty() { 1e-4 } else { (ln_h / tests.len() as f64).exp() };
        let radii: Vec<Option<f64>> = tests.iter().map(|t| t.edge_radius_m).collect();
        let edge_shape = if !radii.is_empty() && radii.iter().all(|r| r.is_some_and(|r| r > 0.0)) {
            let mean = radii.iter().flatten().sum::<f64>() / radii.len() as f64;
            Some(radii.iter().flatten().map(|r| r / mean).collect())
        } else {
            None
        };
        Self {
            wear_state,
            bue_onset: 0.0,
            bue_gate_c: None,
            friction_v_ref_m_min,
            size_h_ref_m,
            edge_shape,
            order_from_rows,
        }
    }

    /// The context with the built-up-edge gate set to the interface temperature `sim` gives at its
    /// start parameters without mechanisms, when it gives a finite one above 20 degC at every test.
    #[must_use]
    pub fn with_interface_gate(mut self, sim: &dyn Simulator, tests: &[CuttingTest]) -> Self {
        let start: Vec<f64> = sim.baseline_params().iter().map(|p| p.start).collect();
        let preds = sim.simulate(tests, &start, &vec![Hooks::NEUTRAL; tests.len()]);
        let t: Option<Vec<f64>> =
            preds.ok().and_then(|p| p.iter().map(|p| p.t_int_c.filter(|t| t.is_finite() && *t > 20.0)).collect());
        self.bue_gate_c = t;
        self
    }

    /// The built-up-edge gate coordinate of test `i` of `tests`: its interface temperature, degC,
    /// when known, else its speed, m/min.
    #[must_use]
    pub fn bue_coordinate(&self, tests: &[CuttingTest], i: usize) -> f64 {
        self.bue_gate_c.as_ref().map_or(tests[i].speed_m_per_s * 60.0, |g| g[i])
    }

    /// The context restricted to the tests at `indices` (for leave-one-condition-out folds).
    #[must_use]
    pub fn subset(&self, indices: &[usize]) -> Self {
        Self {
            wear_state: self.wear_state.as_ref().map(|w| indices.iter().map(|&i| w[i]).collect()),
            bue_onset: self.bue_onset,
            bue_gate_c: self.bue_gate_c.as_ref().map(|w| indices.iter().map(|&i| w[i]).collect()),
            friction_v_ref_m_min: self.friction_v_ref_m_min,
            size_h_ref_m: self.size_h_ref_m,
            edge_shape: self.edge_shape.as_ref().map(|w| indices.iter().map(|&i| w[i]).collect()),
            order_from_rows: self.order_from_rows,
        }
    }
}

/// Whether the rows are monotone (non-decreasing or non-increasing) in `f` with at least two
/// distinct values.
fn sorted_by(tests: &[CuttingTest], f: impl Fn(&CuttingTest) -> f64) -> bool {
    let v: Vec<f64> = tests.iter().map(f).collect();
    let up = v.windows(2).all(|w| w[1] >= w[0]);
    let down = v.windows(2).all(|w| w[1] <= w[0]);
    let varies = v.iter().any(|x| (x - v[0]).abs() > 1e-9 * v[0].abs());
    varies && (up || down)
}
