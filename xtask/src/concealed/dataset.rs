//! One dataset as a user would have it: a design of 5-30 conditions, the "FE run" (the generator at
//! NOMINAL constants with no mechanism: `simulation.csv`) and the recordings (the generator with the
//! nuisance perturbation of every dataset, the hidden mechanism or decoy, and lognormal noise:
//! `recordings.csv`), with the sealed truth.
//!
//! Effect-to-noise ratio (ENR), from the generator's own truth: with d_io = ln y_io(with) -
//! ln y_io(without) for every recorded output o (Fc, Ft, t_c, and T_int when recorded) of condition i,
//! both noise-free at the same perturbed constants, and sigma_o the output's lognormal noise,
//! ENR = sqrt(mean_io (d_io / sigma_o)^2), the RMS effect in noise units. `enr_shape` is the same
//! after removing each output's mean shift (the part a flow-stress level or a gain could absorb). The
//! mechanism's strength is set by bisection on ENR to a target (6 of every 7 datasets of a
//! mechanism aim at ENR 2.3-8, the rest at 0.5-1.8), within its physical range.

use std::fmt::Write as _;

use rand::seq::SliceRandom;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::Serialize;

use super::forms_d::{self, ShapeD};
use super::material::{Cond, Consts, Material, NuisanceScope, Solution, MATERIALS};
use super::mechanism::{self, Mods, Shape};
use super::{detectable, energy, merchant, oxley, Family};

/// Standard normal deviate (Box-Muller).
pub fn std_normal(rng: &mut ChaCha8Rng) -> f64 {
    let u1: f64 = rng.gen_range(1e-12..1.0);
    let u2: f64 = rng.gen_range(0.0..1.0);
    (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos()
}

/// Solves one condition with family `a` or `d` (Oxley, on the shear-angle branch of `phi_hint` when
/// given: [`oxley::solve_near`]), `b` (Merchant + Zorev + Loewen-Shaw, its own solver) or `c` (minimum
/// energy + Coulomb-Tresca + Weiner / Jaeger, [`energy::solve`]); b and c do not use the hint.
pub fn solve(family: Family, c: &Cond, k: &Consts, m: &Mods, phi_hint: Option<f64>) -> Result<Solution, String> {
    match family {
        Family::A | Family::D => oxley::solve_near(c, k, m, phi_hint),
        Family::B => merchant::solve(c, k, m),
        Family::C => energy::solve(c, k, m),
    }
}

/// The sealed truth of one dataset.
#[derive(Debug, Clone, Serialize)]
pub struct Truth {
    /// Dataset index within its family.
    pub index: usize,
    /// `a`, `b`, `c` or `d`.
    pub family: String,
    /// `null`, a mechanism id or a decoy.
    pub hidden: String,
    /// Work material.
    pub material: String,
    /// Number of rows.
    pub conditions: usize,
    /// Lognormal noise per output (Fc, Ft, t_c, T_int).
    pub noise: [f64; 4],
    /// Target ENR (mechanisms), if any.
    pub target_enr: Option<f64>,
    /// ENR (see the module docs).
    pub enr: f64,
    /// ENR after removing each output's mean shift.
    pub enr_shape: f64,
    /// Strength of the mechanism (unit per `mechanism::strength_range`) or decoy parameter.
    pub strength: Option<f64>,
    /// Whether the strength search hit its physical bound before the target.
    pub at_bound: bool,
    /// Edge radius in the simulation and in the truth, um.
    pub edge_radius_um: [f64; 2],
    /// Optional columns written.
    pub columns: Vec<String>,
    /// The perturbed constants (truth) of the recordings.
    pub nuisance: Consts,
    /// ENR left after the generator's own nuisance constants move within their stated ranges
    /// (`detectable.rs`); `None` when a perturbed solve failed.
    pub enr_beyond_nuisance: Option<f64>,
    /// The sum of squares (noise units) of the noise-free effect left by the nuisance and the nearest
    /// rival mechanism in the generator's own form (`detectable::nearest_rival`): about the AICc
    /// by which the hidden form beats that rival's. Mechanisms only; `None` when no rival could be
    /// solved.
    pub rival_chi2: Option<f64>,
    /// That rival.
    pub nearest_rival: Option<String>,
    /// The mechanism's shape parameters.
    pub shape: Shape,
    /// Family d's shape parameters (its forms, `forms_d.rs`); absent in families a, b, c.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shape_d: Option<ShapeD>,
}

/// A generated dataset.
pub struct Dataset {
    /// `recordings.csv` text.
    pub recordings: String,
    /// `simulation.csv` text.
    pub simulation: String,
    /// Truth.
    pub truth: Truth,
    /// Noise-free (recordings without noise, recordings without mechanism, simulation) per row,
    /// [Fc N/m, Ft N/m, t_c m, T_int degC]; for the invariant tests.
    #[cfg_attr(not(test), allow(dead_code))]
    pub clean: [Vec<[f64; 4]>; 3],
}

struct Design {
    conds: Vec<Cond>,
    run_order: Vec<usize>, // run position of each row (design order)
}

fn design(rng: &mut ChaCha8Rng, m: &Material, low_speed: bool) -> Design {
    let vmax = if low_speed { m.speeds.1.min(200.0) } else { m.speeds.1 };
    let vlo = rng.gen_range(m.speeds.0..(m.speeds.0 * 3.0).min(vmax / 2.0));
    let vhi = rng.gen_range((vlo * 2.0).min(vmax)..=vmax);
    let hlo = rng.gen_range(m.feeds.0..0.1f64.min(m.feeds.1 / 2.0));
    let hhi = rng.gen_range((hlo * 2.0).max(0.1).min(m.feeds.1)..=m.feeds.1);
    let rakes: Vec<f64> = {
        let mut pool = [-5.0, -3.0, 0.0, 5.0, 6.0, 10.0];
        pool.shuffle(rng);
        let mut r: Vec<f64> = pool[..if rng.gen_bool(0.3) { 2 } else { 1 }].to_vec();
        r.sort_by(f64::total_cmp);
        r
    };
    let w = (rng.gen_range(1.0f64..4.0) * 10.0).round() / 10.0;
    let geo = |lo: f64, hi: f64, k: usize, i: usize| {
        if k < 2 {
            (lo * hi).sqrt()
        } else {
            lo * (hi / lo).powf(i as f64 / (k - 1) as f64)
        }
    };
    let mut pts: Vec<(f64, f64, f64)> = Vec::new();
    match rng.gen_range(0..3) {
        0 => {
            let nv = rng.gen_range(2..=6usize);
            let nh = rng.gen_range(2..=(30 / (nv * rakes.len())).clamp(2, 5));
            for (ir, r) in rakes.iter().enumerate() {
                for i in 0..nv {
                    for j in 0..nh {
                        if rakes.len() == 1 || (i + j + ir) % 2 == 0 || nv * nh * 2 <= 30 {
                            pts.push((geo(vlo, vhi, nv, i), geo(hlo, hhi, nh, j), *r));
                        }
                    }
                }
            }
        }
        1 => {
            let n = rng.gen_range(5..=30usize);
            for _ in 0..n {
                let v = (rng.gen_range(vlo.ln()..=vhi.ln())).exp();
                let h = (rng.gen_range(hlo.ln()..=hhi.ln())).exp();
                pts.push((v, h, rakes[rng.gen_range(0..rakes.len())]));
            }
        }
        _ => {
            let (nv, nh) = (rng.gen_range(3..=8usize), rng.gen_range(2..=6usize));
            let (vm, hm) = ((vlo * vhi).sqrt(), (hlo * hhi).sqrt());
            for i in 0..nv {
                pts.push((geo(vlo, vhi, nv, i), hm, rakes[0]));
            }
            for j in 0..nh {
                pts.push((vm, geo(hlo, hhi, nh, j), *rakes.last().unwrap_or(&0.0)));
            }
        }
    }
    pts.truncate(30);
    // Repeats of a few conditions in a quarter of the datasets.
    if rng.gen_bool(0.25) && pts.len() < 28 {
        for _ in 0..rng.gen_range(1..=3usize).min(30 - pts.len()) {
            let p = pts[rng.gen_range(0..pts.len())];
            pts.push(p);
        }
    }
    while pts.len() < 5 {
        let p = pts[pts.len() % pts.len().max(1)];
        pts.push((p.0 * 1.3, p.1, p.2));
    }
    let conds: Vec<Cond> = pts
        .iter()
        .map(|&(v, h, r)| Cond { v: v.round() / 60.0, h: (h * 1e3).round() * 1e-6, w: w * 1e-3, rake: r.to_radians() })
        .collect();
    let mut run_order: Vec<usize> = (0..conds.len()).collect();
    if rng.gen_bool(0.5) {
        run_order.shuffle(rng);
    }
    Design { conds, run_order }
}

/// ENR and shape ENR (each output's mean shift removed) of `with` against `without` over the
/// recorded outputs.
pub fn enr(with: &[[f64; 4]], without: &[[f64; 4]], noise: &[f64; 4], outs: usize) -> (f64, f64) {
    let (mut c, mut raw, mut cnt) = (0.0, 0.0, 0usize);
    for o in 0..outs {
        let d: Vec<f64> = with.iter().zip(without).map(|(a, b)| (a[o] / b[o]).ln() / noise[o]).collect();
        let mean = d.iter().sum::<f64>() / d.len() as f64;
        c += d.iter().map(|x| (x - mean).powi(2)).sum::<f64>();
        raw += d.iter().map(|x| x * x).sum::<f64>();
        cnt += d.len();
    }
    ((raw / cnt as f64).sqrt(), (c / cnt as f64).sqrt())
}

/// Generates dataset `index` of `family`, hiding `hidden`; `rank` is its rank among datasets of the
/// same kind (sets the target ENR).
///
/// `material` forces the work material (the material-spread check); `None` draws it from
/// [`MATERIALS`]. `nuisance` says which constants the dataset's nuisance perturbs.
pub fn generate(
    family: Family,
    index: usize,
    hidden: &str,
    rank: usize,
    seed: u64,
    material: Option<&'static Material>,
    nuisance: NuisanceScope,
) -> Result<Dataset, String> {
    let mut rng =
        ChaCha8Rng::seed_from_u64(seed ^ (index as u64 + family.stream()).wrapping_mul(0x9E37_79B9_7F4A_7C15));
    let drawn = rng.gen_range(0..MATERIALS.len());
    let mat = material.unwrap_or(&MATERIALS[drawn]);
    let d = design(&mut rng, mat, hidden == "built_up_edge");
    let n = d.conds.len();
    let nominal = Consts::nominal(mat);
    let truth_k = nominal.perturbed(&mut rng, nuisance);
    let shape = Shape::draw(&mut rng);
    let shape_d = (family == Family::D).then(|| ShapeD::draw(&mut rng));
    let noise =
        [rng.gen_range(0.02..0.05), rng.gen_range(0.02..0.05), rng.gen_range(0.02..0.05), rng.gen_range(0.03..0.05)];
    let col_order = rng.gen_bool(0.6);
    let col_edge = rng.gen_bool(0.45);
    let col_tint = rng.gen_bool(0.25);
    let col_vb = rng.gen_bool(0.2) || (hidden == "flank_wear" && rng.gen_bool(0.3));
    let vb_measured = hidden == "flank_wear" && col_vb && rng.gen_bool(0.6);
    let plough = hidden == "edge_ploughing";
    let r0 = if !plough && rng.gen_bool(0.5) { rng.gen_range(5e-6..30e-6) } else { 0.0 };
    let outs = if col_tint { 4 } else { 3 };
    let is_mech = mechanism::MECHANISMS.contains(&hidden);
    let target = is_mech.then(|| {
        if rank % 7 != 5 {
            (rng.gen_range(2.3f64.ln()..8f64.ln())).exp()
        } else {
            (rng.gen_range(0.5f64.ln()..1.8f64.ln())).exp()
        }
    });
    // The simulation (nominal, no mechanism) and the truth without the mechanism.
    let edge = |s: &Solution, c: &Cond, r: f64| -> [f64; 4] {
        let (pc, pt) = shape.edge.forces(r, c.h, s.k_ab);
        [s.fc + pc, s.ft + pt, s.tc, s.t_int]
    };
    let mut sim = Vec::with_capacity(n);
    let mut base = Vec::with_capacity(n);
    let mut without = Vec::with_capacity(n);
    for c in &d.conds {
        let s = solve(family, c, &nominal, &Mods::none(), None)?;
        sim.push(edge(&s, c, r0));
        let b = solve(family, c, &truth_k, &Mods::none(), None)?;
        without.push(edge(&b, c, r0));
        base.push(b);
    }
    // Run-order quantities: speeds in run order for the wear land.
    let mut by_run: Vec<usize> = (0..n).collect();
    by_run.sort_by_key(|&i| d.run_order[i]);
    let speeds_run: Vec<f64> = by_run.iter().map(|&i| d.conds[i].v).collect();
    let prof_run = match &shape_d {
        // Family d: Usui's wear rate, from each row's k_AB and T_AB without the mechanism.
        Some(sd) => {
            let col = |f: fn(&Solution) -> f64| by_run.iter().map(|&i| f(&base[i])).collect::<Vec<f64>>();
            forms_d::usui_profile(&speeds_run, &col(|b| b.k_ab), &col(|b| b.t_ab), sd.land[3])
        }
        None => mechanism::wear_profile(&speeds_run, shape.taylor_n),
    };
    let v_span = d.conds.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), c| (lo.min(c.v), hi.max(c.v)));
    let mut wear = vec![0.0; n];
    for (p, &i) in by_run.iter().enumerate() {
        wear[i] = prof_run[p];
    }
    let mut tints: Vec<f64> = base.iter().map(|b| b.t_int).collect();
    tints.sort_by(f64::total_cmp);
    let t_gate = tints[((n - 1) as f64 * shape.bue_quantile).round() as usize];
    let in_model = ["tool_chip_friction", "thermal_softening", "heat_partition", "size_effect", "built_up_edge"];
    // Noise-free recordings with mechanism `id` (the hidden one or a rival) at strength `s`.
    let effect_at = |id: &str, s: f64| -> Result<Vec<[f64; 4]>, String> {
        let mut out = Vec::with_capacity(n);
        for (i, c) in d.conds.iter().enumerate() {
            if let Some(sd) = &shape_d {
                let bg = |sol: &Solution| edge(sol, c, r0);
                out.push(forms_d::truth_row(id, s, sd, c, &truth_k, &base[i], wear[i], v_span, &bg)?);
                continue;
            }
            let sol = if in_model.contains(&id) {
                let m = mechanism::mods(family, id, s, &shape, c, &base[i], t_gate);
                solve(family, c, &truth_k, &m, Some(base[i].phi))?
            } else {
                base[i]
            };
            let mut y = edge(&sol, c, if id == "edge_ploughing" { r0 + s } else { r0 });
            if id == "flank_wear" {
                let (pc, pt) = mechanism::wear_land(&shape, s * wear[i], sol.k_ab);
                y[0] += pc;
                y[1] += pt;
            }
            if id == "force_crosstalk" {
                let (fc, ft) = mechanism::channel(s, &shape, y[0], y[1]);
                if fc <= 0.0 || ft <= 0.0 {
                    return Err("crosstalk made a force negative".into());
                }
                y[0] = fc;
                y[1] = ft;
            }
            out.push(y);
        }
        Ok(out)
    };
    let with_at = |s: f64| effect_at(hidden, s); // a rival edge adds to r0 (0 when the edge is hidden)
    let (mut with, mut strength, mut at_bound) = (without.clone(), None, false);
    if let Some(t) = target {
        let (lo, hi) = mechanism::strength_range(family, hidden);
        let (mut a, mut b) = (lo.ln(), hi.ln());
        let mut best: Option<(f64, f64, Vec<[f64; 4]>)> = None;
        match with_at(hi) {
            Ok(y) if enr(&y, &without, &noise, outs).0 < t => {
                at_bound = true;
                best = Some((hi, 0.0, y));
            }
            _ => {
                for _ in 0..14 {
                    let x = 0.5 * (a + b);
                    match with_at(x.exp()) {
                        Ok(y) => {
                            let e = enr(&y, &without, &noise, outs).0;
                            let miss = (e / t).ln().abs();
                            if best.as_ref().map(|bb| miss < bb.1).unwrap_or(true) {
                                best = Some((x.exp(), miss, y));
                            }
                            if miss < 0.04 {
                                break;
                            }
                            if e < t {
                                a = x;
                            } else {
                                b = x;
                            }
                        }
                        Err(_) => b = x,
                    }
                }
            }
        }
        let (s, _, y) = best.ok_or_else(|| format!("{hidden}: no strength gave a solution"))?;
        strength = Some(s);
        with = y;
    }
    // Decoys on the noise-free truth.
    if let Some(g) = mechanism::decoy(hidden, &mut rng, &mut with, &d.run_order) {
        strength = Some(g);
    }
    let (e, e_shape) = enr(&with, &without, &noise, outs);
    let recorded = |s: &Solution, c: &Cond| edge(s, c, r0);
    let (e_beyond, rival) = if hidden == "null" {
        (Some(0.0), None)
    } else {
        let absorber = detectable::nuisance_columns(
            family, &d.conds, &nominal, &truth_k, &base, &without, &noise, outs, &recorded,
        );
        let effect = detectable::effect(&with, &without, &noise, outs);
        let column = |id: &str, s: f64| effect_at(id, s).ok().map(|y| detectable::effect(&y, &without, &noise, outs));
        let rival = absorber
            .as_ref()
            .filter(|_| is_mech)
            .and_then(|a| detectable::nearest_rival(family, hidden, a, &effect, &column));
        (absorber.map(|a| a.left(&effect)), rival)
    };
    // Noise, then the files.
    let rec: Vec<[f64; 4]> =
        with.iter().map(|y| std::array::from_fn(|o| y[o] * (noise[o] * std_normal(&mut rng)).exp())).collect();
    let vb_rec: Vec<f64> =
        (0..n).map(|i| (strength.unwrap_or(0.0) * wear[i] * 1e3 + 0.01 * std_normal(&mut rng)).max(0.0)).collect();
    let mut columns = Vec::new();
    let mut header = String::from("test,speed_m_min,uncut_mm,width_mm,rake_deg,fc_n_per_mm,ft_n_per_mm,chip_mm");
    for (on, name) in
        [(col_edge, "edge_radius_um"), (col_order, "order"), (col_tint, "t_int_c"), (col_vb, "flank_wear_mm")]
    {
        if on {
            header.push(',');
            header.push_str(name);
            columns.push(name.to_string());
        }
    }
    let mut recordings = format!("{header}\n");
    let rows: Vec<usize> = if col_order { (0..n).collect() } else { by_run.clone() };
    let r_rec = if plough { strength.unwrap_or(0.0) } else { r0 };
    for &i in &rows {
        let c = &d.conds[i];
        let y = rec[i];
        let _ = write!(
            recordings,
            "{},{:.0},{:.3},{:.1},{:.0},{:.2},{:.2},{:.4}",
            i + 1,
            c.v * 60.0,
            c.h * 1e3,
            c.w * 1e3,
            c.rake.to_degrees(),
            y[0] / 1e3,
            y[1] / 1e3,
            y[2] * 1e3
        );
        if col_edge {
            let _ = if r_rec > 0.0 { write!(recordings, ",{:.0}", r_rec * 1e6) } else { write!(recordings, ",") };
        }
        if col_order {
            let _ = write!(recordings, ",{}", d.run_order[i] + 1);
        }
        if col_tint {
            let _ = write!(recordings, ",{:.0}", y[3]);
        }
        if col_vb {
            let _ = if vb_measured { write!(recordings, ",{:.3}", vb_rec[i]) } else { write!(recordings, ",") };
        }
        recordings.push('\n');
    }
    let sim_tint = col_tint || rng.gen_bool(0.3);
    let mut simulation = String::from("test,fc_n_per_mm,ft_n_per_mm,chip_mm");
    simulation.push_str(if sim_tint { ",t_int_c\n" } else { "\n" });
    for (i, y) in sim.iter().enumerate() {
        let _ = write!(simulation, "{},{:.2},{:.2},{:.4}", i + 1, y[0] / 1e3, y[1] / 1e3, y[2] * 1e3);
        let _ = if sim_tint { writeln!(simulation, ",{:.0}", y[3]) } else { writeln!(simulation) };
    }
    let truth = Truth {
        index,
        family: family.as_str().into(),
        hidden: hidden.into(),
        material: mat.name.into(),
        conditions: n,
        noise,
        target_enr: target,
        enr: e,
        enr_shape: e_shape,
        enr_beyond_nuisance: e_beyond,
        rival_chi2: rival.as_ref().map(|r| r.1),
        nearest_rival: rival.map(|r| r.0),
        strength,
        at_bound,
        edge_radius_um: [if plough { 0.0 } else { r0 * 1e6 }, r_rec * 1e6],
        columns,
        nuisance: truth_k,
        shape,
        shape_d,
    };
    Ok(Dataset { recordings, simulation, truth, clean: [with, without, sim] })
}
