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
    /// Wear state per test in [0, 1]: VB/VB_max when VB was measured (made non-decreasing in the
    /// run order when that is known), else order/order_max.
    pub wear_state: Option<Vec<f64>>,
    /// Built-up-edge onset on the gate coordinate (chosen on a grid by the fitter): the interface
    /// temperature, degC, when `bue_gate_c` is set, else the speed, m/min.
    pub bue_onset: f64,
    /// Built-up-edge floor on the gate coordinate (0: none): with one, the edge forms in the band
    /// between floor and onset (`mechanism::bue_gates`).
    pub bue_floor: f64,
    /// The baseline's tool-chip interface temperature per test, degC, when the simulator gives it at
    /// every test: the built-up edge is then gated by it (it forms on a cool interface and
    /// disappears as the interface heats, Trent & Wright 2000), else by the speed.
    pub bue_gate_c: Option<Vec<f64>>,
    /// Whether the built-up edge is gated by the speed even though `bue_gate_c` is known (chosen
    /// by the screen with the gate: an edge charted on the speed alone, as in the BUE maps of
    /// Trent & Wright 2000, Sec 5.3, is not ordered by the interface temperature when the feed
    /// varies).
    pub bue_by_speed: bool,
    /// Whether the built-up edge's temperature gate is sharp (`mechanism::BUE_SHARP_WIDTH` in ln T
    /// instead of `mechanism::BUE_WIDTH`), chosen by the screen with the gate (`bue_coordinates`).
    pub bue_sharp: bool,
    /// The baseline's apparent tool-chip friction coefficient per test over its largest value, in
    /// (0, 1], when the simulator gives both forces at every test: `mu_app = F/N = tan(alpha +
    /// atan(Ft/Fc))` (Merchant's force circle), which in Oxley's closure is `k_chip / sigma_N`, the
    /// coefficient below which a Coulomb law caps the interface shear. The hybrid friction law's
    /// shape (`mechanism::hybrid_friction_factor`; Oezel 2006).
    pub friction_load: Option<Vec<f64>>,
    /// The friction law's form, chosen by the refit: false = the shear-factor law, true = the
    /// hybrid Coulomb-Tresca law on `friction_load` (`mechanism::hybrid_friction_factor`).
    pub friction_coulomb: bool,
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
    /// How many tests' measured VB was moved to make the wear non-decreasing in the run order
    /// (0 when VB was not measured, the run order is unknown or VB never falls along it): the
    /// report says so.
    pub vb_tests_smoothed: usize,
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
        let mut vb_tests_smoothed = 0;
        let wear_state: Option<Vec<f64>> = if vb.iter().all(Option::is_some) {
            // One tool's flank wear cannot fall as it cuts: a measured fall along the run order is
            // the scatter of the VB reading, and the wear is its non-decreasing least-squares fit.
            let raw: Vec<f64> = vb.iter().flatten().copied().collect();
            let smooth = run_positions(tests).map_or_else(|| raw.clone(), |pos| monotone_in_run_order(&raw, &pos));
            vb_tests_smoothed = smooth.iter().zip(&raw).filter(|(a, b)| (*a - *b).abs() > 1e-12).count();
            over_max(&smooth)
        } else if let Some(pos) = run_positions(tests) {
            // Row i of n ran i-th when there is no `order` column: state (i + 1) / n, as an
            // `order` column 1..n would give.
            order_from_rows = tests.iter().all(|t| t.order.is_none());
            over_max(&pos)
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
            vb_tests_smoothed,
            bue_onset: 0.0,
            bue_floor: 0.0,
            bue_gate_c: None,
            bue_by_speed: false,
            bue_sharp: false,
            friction_load: None,
            friction_coulomb: false,
            friction_v_ref_m_min,
            size_h_ref_m,
            edge_shape,
            order_from_rows,
        }
    }

    /// The context with what the baseline interface gives, from `sim` at its start parameters
    /// without mechanisms: the built-up-edge gate set to the interface temperature when it is a
    /// finite one above 20 degC at every test, and the friction load ([`Context::friction_load`])
    /// when every test has a finite apparent friction coefficient in (0.01, 10).
    #[must_use]
    pub fn with_baseline_interface(mut self, sim: &dyn Simulator, tests: &[CuttingTest]) -> Self {
        let start: Vec<f64> = sim.baseline_params().iter().map(|p| p.start).collect();
        let Ok(preds) = sim.simulate(tests, &start, &vec![Hooks::NEUTRAL; tests.len()]) else { return self };
        self.bue_gate_c = preds.iter().map(|p| p.t_int_c.filter(|t| t.is_finite() && *t > 20.0)).collect();
        let mu: Option<Vec<f64>> = tests
            .iter()
            .zip(&preds)
            .map(|(t, p)| {
                let angle = t.rake_rad + (p.ft_n_per_m / p.fc_n_per_m).atan();
                let mu = angle.tan();
                (p.fc_n_per_m > 0.0 && angle < 1.5 && mu.is_finite() && (0.01..10.0).contains(&mu)).then_some(mu)
            })
            .collect();
        self.friction_load = mu.and_then(|m| over_max(&m));
        self
    }

    /// The built-up-edge gate coordinate of test `i` of `tests`: its interface temperature, degC,
    /// when known and not `bue_by_speed`, else its speed, m/min.
    #[must_use]
    pub fn bue_coordinate(&self, tests: &[CuttingTest], i: usize) -> f64 {
        match (&self.bue_gate_c, self.bue_by_speed) {
            (Some(g), false) => g[i],
            _ => tests[i].speed_m_per_s * 60.0,
        }
    }

    /// Whether the built-up edge's gate is the sharp temperature gate: `bue_sharp` on the interface
    /// temperature (the speed gate is never sharpened).
    #[must_use]
    pub fn bue_sharp_gate(&self) -> bool {
        self.bue_sharp && self.bue_gated_by_temperature()
    }

    /// The built-up edge's gate width in the log of its coordinate (`mechanism::bue_gate`).
    #[must_use]
    pub fn bue_width(&self) -> f64 {
        if self.bue_sharp_gate() {
            crate::mechanism::BUE_SHARP_WIDTH
        } else {
            crate::mechanism::BUE_WIDTH
        }
    }

    /// Whether the built-up edge's gate coordinate is the interface temperature (else the speed).
    #[must_use]
    pub fn bue_gated_by_temperature(&self) -> bool {
        self.bue_gate_c.is_some() && !self.bue_by_speed
    }

    /// The context restricted to the tests at `indices` (for leave-one-condition-out folds).
    #[must_use]
    pub fn subset(&self, indices: &[usize]) -> Self {
        Self {
            wear_state: self.wear_state.as_ref().map(|w| indices.iter().map(|&i| w[i]).collect()),
            bue_onset: self.bue_onset,
            bue_floor: self.bue_floor,
            bue_gate_c: self.bue_gate_c.as_ref().map(|w| indices.iter().map(|&i| w[i]).collect()),
            bue_by_speed: self.bue_by_speed,
            bue_sharp: self.bue_sharp,
            friction_load: self.friction_load.as_ref().map(|w| indices.iter().map(|&i| w[i]).collect()),
            friction_coulomb: self.friction_coulomb,
            friction_v_ref_m_min: self.friction_v_ref_m_min,
            size_h_ref_m: self.size_h_ref_m,
            edge_shape: self.edge_shape.as_ref().map(|w| indices.iter().map(|&i| w[i]).collect()),
            order_from_rows: self.order_from_rows,
            vb_tests_smoothed: self.vb_tests_smoothed,
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

/// `v` over its largest value, when that is positive.
fn over_max(v: &[f64]) -> Option<Vec<f64>> {
    let max = v.iter().fold(0.0f64, |a, b| a.max(*b));
    (max > 0.0).then(|| v.iter().map(|x| x / max).collect())
}

/// The run position of each test when the run order is known: the `order` column, else the row
/// number (1..n) when the rows are not a listing sorted by thickness or speed.
fn run_positions(tests: &[CuttingTest]) -> Option<Vec<f64>> {
    if tests.iter().all(|t| t.order.is_some()) {
        Some(tests.iter().filter_map(|t| t.order).map(|o| o as f64).collect())
    } else if tests.len() >= 2
        && tests.iter().all(|t| t.order.is_none())
        && !sorted_by(tests, |t| t.uncut_chip_thickness_m)
        && !sorted_by(tests, |t| t.speed_m_per_s)
    {
        Some((1..=tests.len()).map(|i| i as f64).collect())
    } else {
        None
    }
}

/// The least-squares non-decreasing fit of `y` over the run positions `pos` (pool adjacent
/// violators, Barlow et al. 1972): flank wear cannot fall while one tool cuts.
fn monotone_in_run_order(y: &[f64], pos: &[f64]) -> Vec<f64> {
    let mut idx: Vec<usize> = (0..y.len()).collect();
    idx.sort_by(|&a, &b| pos[a].total_cmp(&pos[b]));
    let mut blocks: Vec<(f64, usize)> = Vec::new();
    for &i in &idx {
        blocks.push((y[i], 1));
        while blocks.len() >= 2 && blocks[blocks.len() - 2].0 > blocks[blocks.len() - 1].0 {
            let (m2, n2) = blocks.pop().unwrap_or((0.0, 0));
            let (m1, n1) = blocks.pop().unwrap_or((0.0, 0));
            blocks.push(((m1 * n1 as f64 + m2 * n2 as f64) / (n1 + n2) as f64, n1 + n2));
        }
    }
    let mut out = vec![0.0; y.len()];
    let mut k = 0;
    for (m, n) in blocks {
        for &i in &idx[k..k + n] {
            out[i] = m;
        }
        k += n;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn log(vb_mm: &[f64], order: Option<&[u32]>) -> Vec<CuttingTest> {
        // Speeds and thicknesses unsorted, so that the rows may stand for the run order.
        let (v, h) = ([100.0, 200.0, 150.0, 120.0, 180.0], [0.2, 0.1, 0.15, 0.12, 0.18]);
        (0..vb_mm.len())
            .map(|i| {
                let mut t = CuttingTest::new(format!("t{i}"), v[i % 5] / 60.0, h[i % 5] * 1e-3, 1e-3, 0.0).unwrap();
                t.flank_wear_m = Some(vb_mm[i] * 1e-3);
                t.order = order.map(|o| o[i]);
                t
            })
            .collect()
    }

    #[test]
    fn pool_adjacent_violators_by_hand() {
        // 1, 3, 2, 4 in run order: the violating pair (3, 2) pools to 2.5.
        assert_eq!(monotone_in_run_order(&[1.0, 3.0, 2.0, 4.0], &[1.0, 2.0, 3.0, 4.0]), vec![1.0, 2.5, 2.5, 4.0]);
        // A fall that spans three: 4, 1, 1 pools to 2 each after 0.
        assert_eq!(monotone_in_run_order(&[0.0, 4.0, 1.0, 1.0], &[1.0, 2.0, 3.0, 4.0]), vec![0.0, 2.0, 2.0, 2.0]);
        // The positions, not the listing, set the order: listed as run 3, 1, 2.
        assert_eq!(monotone_in_run_order(&[2.0, 1.0, 3.0], &[3.0, 1.0, 2.0]), vec![2.5, 1.0, 2.5]);
        // Already non-decreasing: unchanged.
        assert_eq!(monotone_in_run_order(&[0.0, 0.0, 1.0], &[1.0, 2.0, 3.0]), vec![0.0, 0.0, 1.0]);
    }

    #[test]
    fn measured_wear_is_made_non_decreasing_in_the_run_order() {
        // VB 0.10, 0.30, 0.20, 0.40 mm in row order: the fall 0.30 -> 0.20 pools to 0.25, two
        // tests move, and the state is VB / 0.40.
        let ctx = Context::of(&log(&[0.1, 0.3, 0.2, 0.4], None));
        let w = ctx.wear_state.unwrap();
        for (a, b) in w.iter().zip([0.25, 0.625, 0.625, 1.0]) {
            assert!((a - b).abs() < 1e-12, "{w:?}");
        }
        assert_eq!(ctx.vb_tests_smoothed, 2);
        // The `order` column sets the run: the same readings run 2, 1, 3, 4 read 0.3, 0.1, 0.2,
        // 0.4 in run order; 0.3 and 0.1 pool to 0.2, which the third reading equals.
        let ctx = Context::of(&log(&[0.1, 0.3, 0.2, 0.4], Some(&[2, 1, 3, 4])));
        let w = ctx.wear_state.unwrap();
        for (a, b) in w.iter().zip([0.5, 0.5, 0.5, 1.0]) {
            assert!((a - b).abs() < 1e-12, "{w:?}");
        }
        assert_eq!(ctx.vb_tests_smoothed, 2);
        // Rising readings are kept as measured.
        let ctx = Context::of(&log(&[0.0, 0.1, 0.2, 0.4], None));
        assert_eq!(ctx.vb_tests_smoothed, 0);
        assert_eq!(ctx.wear_state, Some(vec![0.0, 0.25, 0.5, 1.0]));
    }

    proptest::proptest! {
        /// Pool adjacent violators gives a non-decreasing sequence in the run order, keeps the
        /// readings' sum (each pooled block is its readings' mean) and leaves a non-decreasing
        /// input as it is.
        #[test]
        fn monotone_fit_rises_keeps_the_sum_and_fixes_rising_input(
            y in proptest::collection::vec(0.0f64..0.5, 1..20),
            seed in 0u64..1000,
        ) {
            let n = y.len();
            // A permutation of run positions from the seed (an LCG shuffle; no extra dependency).
            let mut pos: Vec<f64> = (1..=n).map(|i| i as f64).collect();
            let mut r = seed;
            for i in (1..n).rev() {
                r = r.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
                pos.swap(i, (r >> 33) as usize % (i + 1));
            }
            let m = monotone_in_run_order(&y, &pos);
            let mut idx: Vec<usize> = (0..n).collect();
            idx.sort_by(|&a, &b| pos[a].total_cmp(&pos[b]));
            for w in idx.windows(2) {
                proptest::prop_assert!(m[w[1]] >= m[w[0]] - 1e-12);
            }
            proptest::prop_assert!((m.iter().sum::<f64>() - y.iter().sum::<f64>()).abs() < 1e-9);
            let mut rising: Vec<f64> = y.clone();
            rising.sort_by(f64::total_cmp);
            let ident: Vec<f64> = (1..=n).map(|i| i as f64).collect();
            proptest::prop_assert_eq!(monotone_in_run_order(&rising, &ident), rising);
        }
    }
}
