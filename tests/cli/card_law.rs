//! The exported Abaqus card carries the law the identification minimised (issue 11, item 1).
//!
//! `cutcal identify` (converged preset) writes the JC set and the zone fields (the points of
//! Eq 15); `cutcal export` writes the native Johnson-Cook Abaqus card from that set. This test
//! reads the card's numbers back with its own parser and evaluates them with the Johnson-Cook law
//! as the Abaqus Analysis User's Guide documents it ("Johnson-Cook plasticity": homologous
//! temperature 0 below the transition temperature and 1 above melting; "Johnson-Cook rate
//! dependence": `sigma = sigma0 (1 + C ln(epsdot/epsdot0))` for `epsdot >= epsdot0`, the static
//! yield below it). At every zone point that law must equal `JcParams::flow_stress`, the clamped
//! law the converged preset fits; the paper's unclamped Eq 16 differs at the zone edges.

use std::fs;

use cutcal_model::{JcParams, RateTerm};

use super::cutcal;

/// The numbers of the data line after `keyword` (comment lines `**` skipped).
fn data_after(card: &str, keyword: &str) -> Vec<f64> {
    let mut lines = card.lines().skip_while(|l| !l.trim().eq_ignore_ascii_case(keyword)).skip(1);
    let line = lines.find(|l| !l.starts_with("**")).unwrap_or_else(|| panic!("no data after {keyword}"));
    line.split(',').map(|x| x.trim().parse::<f64>().unwrap_or_else(|_| panic!("{line}"))).collect()
}

/// The Abaqus Johnson-Cook law from the card's numbers (MPa, K).
fn abaqus_law(p: &[f64], rate: &[f64], eps: f64, epsdot: f64, t_k: f64) -> f64 {
    let (a, b, n, m, t_melt, t_tr) = (p[0], p[1], p[2], p[3], p[4], p[5]);
    let (c, eps0) = (rate[0], rate[1]);
    let theta = if t_k < t_tr {
        0.0
    } else if t_k > t_melt {
        1.0
    } else {
        (t_k - t_tr) / (t_melt - t_tr)
    };
    let static_yield = (a + b * eps.powf(n)) * (1.0 - theta.powf(m));
    if epsdot >= eps0 {
        static_yield * (1.0 + c * (epsdot / eps0).ln())
    } else {
        static_yield
    }
}

#[test]
fn the_abaqus_card_is_the_law_the_fit_minimised() {
    let dir = tempfile::tempdir().unwrap();
    let p = |f: &str| dir.path().join(f).to_str().unwrap().to_string();
    let o = cutcal(&[
        "identify",
        "--material",
        "fixtures/materials/c38.toml",
        "--tests",
        "fixtures/tests/c38.csv",
        "--test",
        "3",
        "--out-jc",
        &p("jc.toml"),
        "--fields-csv",
        &p("fields.csv"),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let o = cutcal(&[
        "export",
        "--material",
        "fixtures/materials/c38.toml",
        "--jc",
        &p("jc.toml"),
        "--format",
        "abaqus",
        "--out",
        &p("cards"),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let card = fs::read_to_string(dir.path().join("cards").join("c38_abaqus_jc.inp")).unwrap();
    let plastic = data_after(&card, "*PLASTIC, HARDENING=JOHNSON COOK");
    let rate = data_after(&card, "*RATE DEPENDENT, TYPE=JOHNSON COOK");
    assert_eq!((plastic.len(), rate.len()), (6, 2));

    let jc: toml::Table = fs::read_to_string(p("jc.toml")).unwrap().parse().unwrap();
    let g = |k: &str| jc[k].as_float().unwrap();
    let law = JcParams::new(
        g("a_mpa") * 1e6,
        g("b_mpa") * 1e6,
        g("n"),
        g("c"),
        g("m"),
        g("eps0_per_s"),
        g("tm_c"),
        g("tr_c"),
    )
    .unwrap();

    let fields = fs::read_to_string(p("fields.csv")).unwrap();
    let (mut worst, mut below_eps0, mut unclamped_gap) = (0f64, 0, 0f64);
    for line in fields.lines().skip(1) {
        let v: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        let (eps, epsdot, t_c) = (v[3], v[4], v[7]);
        let card_mpa = abaqus_law(&plastic, &rate, eps, epsdot, t_c + 273.15);
        let fitted_mpa = law.flow_stress(eps, epsdot, t_c) / 1e6;
        worst = worst.max((card_mpa / fitted_mpa - 1.0).abs());
        if epsdot < law.eps0_per_s {
            below_eps0 += 1;
            if epsdot > 0.0 {
                let paper = law.flow_stress_with(RateTerm::Unclamped, eps, epsdot, t_c) / 1e6;
                unclamped_gap = unclamped_gap.max((paper / fitted_mpa - 1.0).abs());
            }
        }
    }
    println!("card vs fitted law: max rel. diff {worst:.2e}; {below_eps0} points below eps0, unclamped Eq 16 off by up to {:.0} %", 100.0 * unclamped_gap);
    // The card prints numbers to finite precision; the law is the same to that precision.
    assert!(worst < 1e-5, "card law departs from the fitted law by {worst}");
    // The zone edges have rates below eps0, where the unclamped Eq 16 is not the card's law.
    assert!(below_eps0 >= 2, "{below_eps0}");
    assert!(unclamped_gap > 0.05, "{unclamped_gap}");
}
