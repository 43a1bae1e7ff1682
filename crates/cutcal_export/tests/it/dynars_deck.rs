//! A real third-party LS-DYNA parser (the `dynars` crate, schema generated from PyDyna's field
//! database; fe-cards.md §5.1b) reads every exported deck: keyword classes, JC and thermal
//! values, contact fields, EOS link and table-curve order (fe-cards.md §6 pitfalls 1-5).

use cutcal_export::physics::eq17_mu;
use cutcal_export::{render, Dialect};
use cutcal_model::Friction;
use dynars::deck::parse_deck;

use crate::common;

/// Every keyword the deck may contain, with the dynars schema that must parse it (dynars maps
/// by canonical base name; a keyword without a schema would be read raw, so it is an error).
const EXPECTED_SCHEMA: &[&str] = &[
    "PART",
    "SECTION_SOLID",
    "MAT_JOHNSON_COOK",
    "EOS_LINEAR_POLYNOMIAL",
    "MAT_THERMAL_ISOTROPIC_TD_LC",
    "MAT_ELASTIC",
    "DEFINE_CURVE",
    "CONTACT_SURFACE_TO_SURFACE_THERMAL_FRICTION",
    "DEFINE_TABLE",
    "HOURGLASS",
    "INITIAL_TEMPERATURE_SET",
    "CONTROL_SOLUTION",
    "CONTROL_THERMAL_SOLVER",
    "CONTROL_THERMAL_TIMESTEP",
    "CONTROL_TERMINATION",
];

/// Keywords dynars 1.1 has no schema for (parsed and class-checked by PyDyna in `pydyna.rs`).
const NO_DYNARS_SCHEMA: &[&str] = &["HOURGLASS"];

/// Relative tolerance of a 10-column field: 6 significant digits (templates::SIG_D10).
fn close6(got: f64, want: f64) -> bool {
    (got - want).abs() <= 0.5e-5 * want.abs() * (1.0 + 1e-9)
}

fn f64_of(k: &dynars::model::Keyword<'_>, name: &str) -> f64 {
    k.field(name)
        .and_then(|f| f.as_f64())
        .unwrap_or_else(|| panic!("{} line {}: field {name} not read", k.name(), k.line()))
}

#[test]
fn dynars_reads_back_every_exported_deck() {
    let opts = common::options();
    let dir = tempfile::tempdir().unwrap();
    for case in common::cases() {
        let prov = common::provenance(&case);
        let files = render(Dialect::LsDyna, &common::input(&case, &prov, &opts)).unwrap();
        let path = dir.path().join(&files[0].name);
        std::fs::write(&path, &files[0].contents).unwrap();
        let deck = parse_deck(&path).unwrap();
        let file = deck.files().next().unwrap();

        // Keyword classes, in file order (both parsers silently misread unknown variants).
        let names: Vec<String> = file
            .keywords()
            .map(|k| k.name().to_string())
            .filter(|n| !matches!(n.as_str(), "KEYWORD" | "TITLE" | "END"))
            .collect();
        let written: Vec<String> = files[0]
            .contents
            .lines()
            .filter(|l| l.starts_with('*'))
            .map(|l| l[1..].trim().to_string())
            .filter(|n| !matches!(n.as_str(), "KEYWORD" | "TITLE" | "END"))
            .collect();
        assert_eq!(names, written, "{}: dynars saw a different keyword sequence", case.key);
        for k in file.keywords().filter(|k| !matches!(k.name(), "KEYWORD" | "TITLE" | "END")) {
            let base = k.base();
            if !k.has_schema() {
                // dynars 1.1 has no schema for these; the PyDyna test (pydyna.rs) checks them.
                assert!(NO_DYNARS_SCHEMA.contains(&base.as_str()), "{}: {} has no dynars schema", case.key, k.name());
                continue;
            }
            let schema = dynars::keywords::find(&base).map(|s| s.name);
            assert!(
                EXPECTED_SCHEMA.contains(&base.as_str()) && schema == Some(base.as_str()),
                "{}: {} parsed with schema {schema:?}",
                case.key,
                k.name()
            );
        }

        // JC and thermal values of MAT_015 (fe-cards.md §1.1 unit table, t-mm-s-K).
        let part = deck.part(1).unwrap();
        let mat = part.material().unwrap();
        assert_eq!(mat.base(), "MAT_JOHNSON_COOK");
        let jc = case.jc;
        let wp = &case.workpiece;
        let want = [
            ("a", jc.a_pa * 1e-6),
            ("b", jc.b_pa * 1e-6),
            ("n", jc.n),
            ("c", jc.c),
            ("m", jc.m),
            ("tm", jc.tm_c + 273.15),
            ("tr", jc.tr_c + 273.15),
            ("epso", jc.eps0_per_s),
            ("ro", wp.thermal.density.value(wp.room_c) * 1e-12),
            ("cp", wp.thermal.specific_heat(wp.room_c) * 1e6),
        ];
        for (name, v) in want {
            let got = f64_of(&mat, name);
            assert!(close6(got, v), "{} {name}: read {got}, exported {v}", case.key);
        }

        // Pitfall 1: a MAT_015 solid part needs an EOS.
        assert!(part.field("eosid").and_then(|f| f.as_i64()).unwrap_or(0) > 0);
        assert_eq!(part.eos().map(|e| e.base()).as_deref(), Some("EOS_LINEAR_POLYNOMIAL"));

        // Contact: heat transfer and friction fields.
        let contact = deck.keywords("CONTACT_SURFACE_TO_SURFACE_THERMAL_FRICTION").next().unwrap();
        // Paper Sec 5.1: 1e5 kW/(m^2 K) = 1e8 W/(m^2 K) -> x1e-3 -> 1e5 N/(s mm K).
        assert!(close6(f64_of(&contact, "h0"), 1e5));
        match case.interface.friction {
            Friction::PressureDependentShear { m0, beta_per_pa } => {
                // k at the default contact temperature T* = 0.5 (no interface temperature given),
                // written out from paper Eq 16 at eps = 2, epsdot = 1e4 1/s:
                // (A + B 2^n)(1 + C ln(1e4/eps0))(1 - 0.5^m)/sqrt(3).
                let k = (jc.a_pa + jc.b_pa * 2f64.powf(jc.n))
                    * (1.0 + jc.c * (1e4 / jc.eps0_per_s).ln())
                    * (1.0 - 0.5f64.powf(jc.m))
                    / 3f64.sqrt();
                assert!(close6(f64_of(&contact, "fs"), 2.0));
                assert!(close6(f64_of(&contact, "vc"), m0 * k * 1e-6));
                let tbid = f64_of(&contact, "fd");
                let table = deck.keywords("DEFINE_TABLE").next().unwrap();
                assert!(close6(f64_of(&table, "tbid"), tbid));
                // Pitfall 4: the curves follow the table, one per pressure, in order.
                let kws: Vec<_> = file.keywords().collect();
                let at = kws.iter().position(|k| k.base() == "DEFINE_TABLE").unwrap();
                // Data rows: the title line (for `_TITLE`), the TBID card, then one value per row.
                let skip = if table.name().ends_with("_TITLE") { 2 } else { 1 };
                let pressures: Vec<f64> =
                    table.cards().skip(skip).map(|c| c.raw(0).unwrap().trim().parse::<f64>().unwrap()).collect();
                assert_eq!(pressures.len(), opts.contact_pressures_pa.len());
                for (i, p_mpa) in pressures.iter().enumerate() {
                    let curve = &kws[at + 1 + i];
                    assert_eq!(curve.base(), "DEFINE_CURVE");
                    let mu: f64 = curve.card(1).unwrap().raw(1).unwrap().trim().parse().unwrap();
                    let want = eq17_mu(m0, beta_per_pa, k, p_mpa * 1e6);
                    assert!((mu - want).abs() <= 1e-8 * want, "{} P = {p_mpa}: mu {mu} vs {want}", case.key);
                }
            }
            Friction::Coulomb { mu } => {
                assert!(close6(f64_of(&contact, "fs"), mu));
                assert!(close6(f64_of(&contact, "fd"), mu));
                assert_eq!(deck.keywords("DEFINE_TABLE").count(), 0);
            }
        }
    }
}
