//! The built-up edge's gate (design note M9; Trent & Wright 2000): the smooth indicator on its gate
//! coordinate (the interface temperature, or the speed) and the candidate onsets the fitter chooses
//! from.

use cutcal_model::CuttingTest;

use crate::context::Context;

/// Smooth indicator of the built-up edge on its gate coordinate (interface temperature, degC, or
/// speed, m/min; `Context::bue_coordinate`): 1 well below the onset, 0 well above.
#[must_use]
pub fn bue_indicator(coordinate: f64, onset: f64) -> f64 {
    // Logistic in the log of the coordinate with a width of 10 % of the onset.
    1.0 / (1.0 + ((coordinate.max(1e-9) / onset.max(1e-9)).ln() / 0.1).exp())
}

/// The distinct positive gate coordinates of the tests, ascending (values within 0.1 % are one).
fn gate_values(tests: &[CuttingTest], ctx: &Context) -> Vec<f64> {
    let mut v: Vec<f64> = (0..tests.len()).map(|i| ctx.bue_coordinate(tests, i)).filter(|x| *x > 0.0).collect();
    v.sort_by(f64::total_cmp);
    v.dedup_by(|a, b| (*a - *b).abs() <= 1e-3 * b.abs());
    v
}

/// Candidate built-up-edge onsets on the gate coordinate: geometric midpoints between its distinct
/// values that leave at least a third of them (and at least two) out of the BUE regime; at most 8,
/// evenly spread over the ranks. An edge over nearly every condition is a uniform rake change, which
/// friction or softening explains as well: the onset is identified only with conditions on both
/// sides (with two above it, friction and softening datasets were named `built_up_edge`).
#[must_use]
pub fn bue_onsets(tests: &[CuttingTest], ctx: &Context) -> Vec<f64> {
    let v = gate_values(tests, ctx);
    if v.len() < 2 {
        return Vec::new();
    }
    let above = 2.max(v.len().div_ceil(3));
    let all: Vec<f64> = v.windows(2).map(|w| (w[0] * w[1]).sqrt()).take(v.len().saturating_sub(above).max(1)).collect();
    if all.len() <= 8 {
        return all;
    }
    (0..8).map(|k| all[k * (all.len() - 1) / 7]).collect()
}

/// Candidate gates `(onset, floor)` of the built-up edge: every onset of [`bue_onsets`] with no
/// floor (`0`: the edge down to the coolest test), and with up to three floors below it, the
/// geometric midpoints that leave at least two gate values below the floor and two between floor
/// and onset. A floor makes the edge a band on the gate coordinate: the edge's height rises from
/// the lowest speeds to a peak and vanishes on a hot interface (Trent & Wright 2000, Sec 5.3;
/// Childs et al. 2000, Sec 1.4).
#[must_use]
pub fn bue_gates(tests: &[CuttingTest], ctx: &Context) -> Vec<(f64, f64)> {
    let v = gate_values(tests, ctx);
    let mut out = Vec::new();
    for onset in bue_onsets(tests, ctx) {
        out.push((onset, 0.0));
        let below = v.iter().filter(|x| **x < onset).count();
        let floors: Vec<f64> = (1..below.saturating_sub(2)).map(|j| (v[j] * v[j + 1]).sqrt()).collect();
        let picks = floors.len().min(3);
        for k in 0..picks {
            let idx = if picks == 1 { 0 } else { k * (floors.len() - 1) / (picks - 1) };
            out.push((onset, floors[idx]));
        }
    }
    out.extend(rising_floors(&v).into_iter().map(|floor| (f64::INFINITY, floor)));
    out
}

/// Floors of the rising gate: the edge above a floor with no onset in the design (`onset =
/// infinity`), the rising side of the edge's band when the design stops below the coordinate at
/// which it vanishes (Trent & Wright 2000, Sec 5.3: the edge's height grows with speed from the
/// lowest speeds to a peak). The mirror of [`bue_onsets`]: geometric midpoints that leave at least
/// a third of the gate values (and at least two) below the floor and two above it; at most 4,
/// evenly spread over the ranks.
fn rising_floors(v: &[f64]) -> Vec<f64> {
    let below = 2.max(v.len().div_ceil(3));
    if v.len() < below + 2 {
        return Vec::new();
    }
    let all: Vec<f64> = (below - 1..=v.len() - 3).map(|j| (v[j] * v[j + 1]).sqrt()).collect();
    if all.len() <= 4 {
        return all;
    }
    (0..4).map(|k| all[k * (all.len() - 1) / 3]).collect()
}

/// The gate coordinates the screen offers the built-up edge, as contexts: `ctx` itself, and with
/// [`Context::bue_by_speed`] set when `ctx` is gated by the interface temperature, at least three
/// speeds were tested and the speed orders the tests differently from the temperature (where it
/// orders them alike, its gates are the same partitions of the tests). A speed gate counts as one
/// more grid-chosen parameter (`ftest::grid_chosen`), and the calibrated null repeats the choice.
#[must_use]
pub fn bue_coordinates(tests: &[CuttingTest], ctx: &Context) -> Vec<Context> {
    let mut out = vec![ctx.clone()];
    if !ctx.bue_gated_by_temperature() {
        return out;
    }
    let mut by_speed = ctx.clone();
    by_speed.bue_by_speed = true;
    let order = |c: &Context| {
        let mut idx: Vec<usize> = (0..tests.len()).collect();
        idx.sort_by(|&a, &b| c.bue_coordinate(tests, a).total_cmp(&c.bue_coordinate(tests, b)));
        idx
    };
    if gate_values(tests, &by_speed).len() >= 3 && order(ctx) != order(&by_speed) {
        out.push(by_speed);
    }
    out
}

/// The built-up edge's gate at `coordinate`: [`bue_indicator`] below the onset (1 with no onset,
/// `onset = infinity`: the rising gate of [`bue_gates`]), times the rise above the floor when
/// there is one (`floor > 0`).
#[must_use]
pub fn bue_gate(coordinate: f64, onset: f64, floor: f64) -> f64 {
    let upper = if onset.is_finite() { bue_indicator(coordinate, onset) } else { 1.0 };
    if floor > 0.0 {
        upper * (1.0 - bue_indicator(coordinate, floor))
    } else {
        upper
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One test per interface temperature in `temps_c` (same cut), with the gate set to them.
    fn gated(temps_c: &[f64]) -> (Vec<CuttingTest>, Context) {
        let t = |i: usize| CuttingTest::new(format!("t{i}"), 2.0, 0.1e-3, 1e-3, 0.0).unwrap();
        let tests: Vec<CuttingTest> = (0..temps_c.len()).map(t).collect();
        let mut ctx = Context::of(&tests);
        ctx.bue_gate_c = Some(temps_c.to_vec());
        (tests, ctx)
    }

    #[test]
    fn bue_onsets_leave_a_third_of_the_gate_values_above() {
        // Nine interface temperatures 400, 450, ..., 800 degC: a third (3) must stay above the
        // onset, so the candidates are the 6 midpoints below the seventh value, the last one
        // sqrt(650 * 700); with three values, two stay above and one midpoint remains.
        let (tests, ctx) = gated(&(0..9).map(|i| 400.0 + 50.0 * i as f64).collect::<Vec<_>>());
        let on = bue_onsets(&tests, &ctx);
        assert_eq!(on.len(), 6);
        assert!((on[5] - (650.0f64 * 700.0).sqrt()).abs() < 1e-9, "{on:?}");
        let (tests3, ctx3) = gated(&[400.0, 500.0, 600.0]);
        assert_eq!(bue_onsets(&tests3, &ctx3), vec![(400.0f64 * 500.0).sqrt()]);
    }

    #[test]
    fn bue_gates_add_floors_that_leave_two_values_below_and_two_in_the_band() {
        // Nine interface temperatures 400, 450, ..., 800 degC and the six onsets above. An onset
        // with b gate values below it takes the floors between values j and j + 1 for j = 1..b-3
        // (two values below the floor, two in the band): none for b = 1, 2, 3; one for b = 4
        // (sqrt(450 * 500)); two for b = 5; three for b = 6. 6 + 1 + 2 + 3 = 12 gates, and the 4
        // rising gates of `rising_gates_leave_a_third_below_and_two_above`.
        let (tests, ctx) = gated(&(0..9).map(|i| 400.0 + 50.0 * i as f64).collect::<Vec<_>>());
        let g = bue_gates(&tests, &ctx);
        assert_eq!(g.len(), 16, "{g:?}");
        assert_eq!(g.iter().filter(|(o, _)| o.is_infinite()).count(), 4);
        let mid = |a: f64, b: f64| (a * b).sqrt();
        assert!(g.contains(&(mid(550.0, 600.0), mid(450.0, 500.0))));
        assert!(g.contains(&(mid(650.0, 700.0), mid(550.0, 600.0))));
        assert!(!g.contains(&(mid(650.0, 700.0), mid(600.0, 650.0))), "one value in the band");
        assert!(!g.contains(&(mid(650.0, 700.0), mid(400.0, 450.0))), "one value below the floor");
        assert_eq!(g.iter().filter(|(_, f)| *f == 0.0).count(), 6);
    }

    #[test]
    fn rising_gates_leave_a_third_below_and_two_above() {
        // Nine values 400, 450, ..., 800: three stay below the floor and two above, so the floors
        // are the midpoints after the 3rd to the 7th value (j = 2..6, five), spread to four over
        // the ranks (j = 2, 3, 4, 6). Four values: two below and two above, one floor. Three
        // values: none.
        let v: Vec<f64> = (0..9).map(|i| 400.0 + 50.0 * i as f64).collect();
        let mid = |a: f64, b: f64| (a * b).sqrt();
        let want = [mid(500.0, 550.0), mid(550.0, 600.0), mid(600.0, 650.0), mid(700.0, 750.0)];
        assert_eq!(rising_floors(&v), want);
        assert_eq!(rising_floors(&[400.0, 500.0, 600.0, 700.0]), vec![mid(500.0, 600.0)]);
        assert!(rising_floors(&[400.0, 500.0, 600.0]).is_empty());
        // With no onset the gate is the rise above the floor alone: 1 - 1 / (1 + (T / T_f)^10),
        // 1/2 at the floor, (6/5)^10 / (1 + (6/5)^10) = 0.860952 at 600 over a 500 degC floor.
        assert!((bue_gate(500.0, f64::INFINITY, 500.0) - 0.5).abs() < 1e-12);
        assert!((bue_gate(600.0, f64::INFINITY, 500.0) - 0.860_952).abs() < 1e-6);
    }

    #[test]
    fn bue_gate_is_a_band_with_a_floor() {
        // Onset 700, floor 500 degC (logistic width 0.1 in ln T, so each indicator is
        // 1 / (1 + (T / T_0)^10)): half the upper indicator at the floor; at 600 degC
        // 1 / (1 + (6/7)^10) x (1 - 1 / (1 + (6/5)^10)) = 0.823684 x 0.860952 = 0.709152; at 400 degC
        // the floor's indicator is 1 / (1 + 0.8^10) = 0.903037; near 0 at 400 and 800 degC.
        assert!((bue_gate(500.0, 700.0, 500.0) - 0.5 * bue_indicator(500.0, 700.0)).abs() < 1e-12);
        assert!((bue_gate(600.0, 700.0, 500.0) - 0.709_152).abs() < 1e-6, "{}", bue_gate(600.0, 700.0, 500.0));
        let floor_indicator = 1.0 / (1.0 + 0.8f64.powi(10));
        assert!((floor_indicator - 0.903_037).abs() < 1e-6);
        assert!((bue_gate(400.0, 700.0, 500.0) - bue_indicator(400.0, 700.0) * (1.0 - floor_indicator)).abs() < 1e-12);
        assert!(bue_gate(400.0, 700.0, 500.0) < 0.1 && bue_gate(800.0, 700.0, 500.0) < 0.3);
        // No floor: the one-sided gate.
        assert_eq!(bue_gate(400.0, 700.0, 0.0), bue_indicator(400.0, 700.0));
    }

    #[test]
    fn bue_indicator_switches_at_onset() {
        // Logistic in ln V with width 0.1: at V = onset it is 1/2; at V = 2 onset it is 1/(1 + e^6.93).
        assert!((bue_indicator(80.0, 80.0) - 0.5).abs() < 1e-12);
        assert!(bue_indicator(160.0, 80.0) < 1e-3 && bue_indicator(40.0, 80.0) > 0.999);
    }

    #[test]
    fn the_speed_is_offered_as_a_gate_coordinate_where_it_orders_the_tests_otherwise() {
        // Four cuts at 60, 90, 120 and 150 m/min. Interface temperatures rising with the speed
        // order them alike: the temperature alone. The slowest cut hotter than the next two (a
        // thicker cut) orders them otherwise: the speed as well, with the speed as its coordinate
        // and one more grid-chosen parameter. Without a temperature the speed is the only one.
        let tests: Vec<CuttingTest> = [60.0, 90.0, 120.0, 150.0]
            .iter()
            .enumerate()
            .map(|(i, v)| CuttingTest::new(format!("t{i}"), v / 60.0, 0.1e-3, 1e-3, 0.0).unwrap())
            .collect();
        let mut ctx = Context::of(&tests);
        ctx.bue_gate_c = Some(vec![500.0, 550.0, 600.0, 650.0]);
        assert_eq!(bue_coordinates(&tests, &ctx).len(), 1);
        ctx.bue_gate_c = Some(vec![620.0, 550.0, 600.0, 650.0]);
        let c = bue_coordinates(&tests, &ctx);
        assert_eq!(c.len(), 2);
        assert!(c[0].bue_gated_by_temperature() && !c[1].bue_gated_by_temperature());
        assert!((c[1].bue_coordinate(&tests, 0) - 60.0).abs() < 1e-9);
        let grid = |c: &Context| crate::ftest::grid_chosen(crate::mechanism::MechanismId::BuiltUpEdge, c);
        assert_eq!((grid(&c[0]), grid(&c[1])), (1, 2));
        ctx.bue_gate_c = None;
        assert_eq!(bue_coordinates(&tests, &ctx).len(), 1);
    }
}
