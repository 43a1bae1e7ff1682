//! Prints the extended-Oxley predictions over a fixed grid of conditions as CSV (stdout): the
//! generator of `fixtures/reference/oxley-solver-grid.csv`, which pins the solver's results so that
//! a faster solve path can be checked against them (`tests/it/oxley_fast_path.rs`).
//!
//! Run: `cargo run -p cutcal_model --release --example oxley_grid > fixtures/reference/oxley-solver-grid.csv`
//! (the provenance header names the commit whose solver produced the stored numbers).
// Tests compare bit-identical results on purpose (determinism, warm against cold paths), print
// what they measure, and reject NaN with negated comparisons.
#![allow(clippy::float_cmp, clippy::print_stdout, clippy::print_stderr, clippy::neg_cmp_op_on_partial_ord)]

use cutcal_model::oxley::{self, CuttingConditions, OxleyOptions, Physics};
use cutcal_model::{JcParams, Material, ModelError, TempPolynomial, ThermalProperties};

/// AA6082, Ertürk et al. 2020 Table 3 properties (as fixtures/materials/aa6082.toml).
fn aa6082() -> Material {
    Material {
        name: "AA6082".into(),
        thermal: ThermalProperties {
            rho_cp: TempPolynomial::new(vec![2.4, 0.0013, -7.17e-7]).unwrap().scaled(1e6),
            density: TempPolynomial::constant(2700.0),
            conductivity: TempPolynomial::new(vec![258.511, -0.1116, -5e-5]).unwrap(),
            valid_from_c: 20.0,
            valid_to_c: 560.0,
        },
        yield_strength: None,
        melting_c: 582.0,
        room_c: 20.0,
        elastic: None,
    }
}

/// One case family of the grid.
struct Family {
    label: &'static str,
    material: Material,
    jc: JcParams,
    work_c: f64,
    options: OxleyOptions,
    physics: Physics,
    speeds_m_min: &'static [f64],
    t1_mm: &'static [f64],
    rakes_deg: &'static [f64],
}

fn kind(e: &ModelError) -> &'static str {
    match e {
        ModelError::NoSolution { .. } => "NoSolution",
        ModelError::NoConvergence { .. } => "NoConvergence",
        ModelError::AboveMelting { .. } => "AboveMelting",
        _ => "other",
    }
}

fn main() {
    // Jaspers & Dautzenberg 2002 (AISI 1045); Ertürk et al. 2020 Table 5 (AA6082).
    let jc_1045 = JcParams::new(553.1e6, 600.8e6, 0.234, 0.0134, 1.0, 1.0, 1460.0, 25.0).unwrap();
    let jc_6082 = JcParams::new(250e6, 61e6, 0.43, 0.034, 1.067, 1.0, 582.0, 20.0).unwrap();
    let speeds: &[f64] = &[40.0, 100.0, 200.0, 350.0, 550.0];
    let feeds: &[f64] = &[0.03, 0.08, 0.15, 0.25, 0.38];
    let rakes: &[f64] = &[-10.0, -3.0, 5.0, 12.0, 19.0];
    let families = [
        Family {
            label: "aisi1045_wide",
            material: cutcal_model::reference::aisi1045_lalwani2009(),
            jc: jc_1045,
            work_c: 25.0,
            options: OxleyOptions::wide(),
            physics: Physics::baseline(),
            speeds_m_min: speeds,
            t1_mm: feeds,
            rakes_deg: rakes,
        },
        Family {
            label: "aa6082_wide",
            material: aa6082(),
            jc: jc_6082,
            work_c: 20.0,
            options: OxleyOptions::wide(),
            physics: Physics::baseline(),
            speeds_m_min: speeds,
            t1_mm: feeds,
            rakes_deg: rakes,
        },
        Family {
            label: "aisi1045_lalwani",
            material: cutcal_model::reference::aisi1045_lalwani2009(),
            jc: jc_1045,
            work_c: 25.0,
            options: OxleyOptions::lalwani2009(),
            physics: Physics::baseline(),
            speeds_m_min: &[100.0, 200.0, 400.0],
            t1_mm: &[0.1, 0.2, 0.3],
            rakes_deg: &[-7.0, 0.0, 10.0],
        },
        Family {
            label: "aisi1045_edge25um",
            material: cutcal_model::reference::aisi1045_lalwani2009(),
            jc: jc_1045,
            work_c: 25.0,
            options: OxleyOptions::wide(),
            physics: Physics::with_tool(Some(25e-6), Some(0.1e-3)).unwrap(),
            speeds_m_min: &[100.0, 300.0],
            t1_mm: &[0.05, 0.2],
            rakes_deg: &[-5.0, 8.0],
        },
    ];
    println!(
        "family,speed_m_min,uncut_mm,rake_deg,status,phi_rad,c0,delta,fc_n_per_m,ft_n_per_m,chip_m,contact_m,t_ab_c,t_int_c,delta_at_bound,delta_poorly_determined"
    );
    for f in &families {
        for &v in f.speeds_m_min {
            for &t1 in f.t1_mm {
                for &rake in f.rakes_deg {
                    let cond = CuttingConditions::new(v / 60.0, t1 * 1e-3, 1e-3, rake.to_radians(), f.work_c).unwrap();
                    match oxley::predict(&f.material, &f.jc, &cond, &f.options, &f.physics) {
                        Ok(p) => println!(
                            "{},{v},{t1},{rake},ok,{:?},{:?},{:?},{:?},{:?},{:?},{:?},{:?},{:?},{},{}",
                            f.label,
                            p.phi_rad,
                            p.c0,
                            p.delta,
                            p.cutting_force_n_per_m,
                            p.feed_force_n_per_m,
                            p.chip_thickness_m,
                            p.contact_length_m,
                            p.temperature_ab_c,
                            p.temperature_int_c,
                            p.flags.delta_at_bound,
                            p.flags.delta_poorly_determined
                        ),
                        Err(e) => println!("{},{v},{t1},{rake},{},,,,,,,,,,,", f.label, kind(&e)),
                    }
                }
            }
        }
    }
}
