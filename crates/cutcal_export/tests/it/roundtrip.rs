//! Property tests over random JC sets: no LS-DYNA field overflows its column, render -> parse ->
//! the same numbers to the printed precision (LS-DYNA 6 digits, Abaqus 7, MatML 9), and NaN or
//! infinity anywhere in the input is an error for every dialect, never rendered.

use cutcal_export::{render, render_all, Dialect, ExportError};
use cutcal_model::{Friction, Interface, JcParams, TempPolynomial};
use proptest::prelude::*;

use crate::common;

/// Relative tolerance of `sig` significant digits (half an ulp of the last printed digit).
fn close(got: f64, want: f64, sig: i32) -> bool {
    (got - want).abs() <= 0.5 * 10f64.powi(1 - sig) * want.abs() * (1.0 + 1e-9)
}

/// Splits one LS-DYNA data card into its fields: comma free format, or fixed `width` columns
/// (asserting that no value straddles a column boundary, fe-cards.md §1.1).
fn dyna_fields(line: &str, width: usize) -> Result<Vec<String>, String> {
    if line.contains(',') {
        return Ok(line.split(',').map(|s| s.trim().to_string()).collect());
    }
    if line.len() > 8 * width.max(10) {
        return Err(format!("line longer than 80 columns: {line:?}"));
    }
    let bytes = line.as_bytes();
    let mut out = Vec::new();
    for start in (0..line.len()).step_by(width) {
        let window = &line[start..(start + width).min(line.len())];
        // A value that starts in the previous column would leave no blank before this window.
        if start > 0 && bytes[start - 1] != b' ' && bytes[start] != b' ' {
            return Err(format!("value straddles column {start}: {line:?}"));
        }
        let t = window.trim();
        if !t.is_empty() && t.parse::<f64>().is_err() {
            return Err(format!("field {t:?} is not a number: {line:?}"));
        }
        out.push(t.to_string());
    }
    Ok(out)
}

/// Checks every data card of a deck; returns the MAT_JOHNSON_COOK cards (after the title).
fn check_deck(deck: &str) -> Result<Vec<Vec<String>>, String> {
    let mut keyword = String::new();
    let mut card = 0usize;
    let mut jc_cards = Vec::new();
    for line in deck.lines() {
        if let Some(k) = line.strip_prefix('*') {
            keyword = k.trim().to_string();
            card = 0;
            continue;
        }
        if line.starts_with('$') {
            continue;
        }
        let is_title = card == 0 && (keyword.ends_with("_TITLE") || keyword == "TITLE" || keyword == "PART");
        if !is_title {
            let data_card = card - usize::from(keyword.ends_with("_TITLE") || keyword == "PART");
            let wide = (keyword.starts_with("DEFINE_CURVE") || keyword.starts_with("DEFINE_TABLE")) && data_card > 0;
            let fields = dyna_fields(line, if wide { 20 } else { 10 })?;
            if keyword == "MAT_JOHNSON_COOK_TITLE" {
                jc_cards.push(fields);
            }
        } else if line.contains(',') || line.len() > 80 {
            return Err(format!("bad title line {line:?}"));
        }
        card += 1;
    }
    Ok(jc_cards)
}

fn jc_strategy() -> impl Strategy<Value = JcParams> {
    (3.0..12.0f64, 3.0..12.0f64, 0.0..2.0f64, 0.0..1.0f64, 0.1..10.0f64, -3.0..0.0f64, 600.0..3000.0f64, 0.0..19.0f64)
        .prop_map(|(la, lb, n, c, m, le, tm, tr)| JcParams {
            a_pa: 10f64.powf(la),
            b_pa: 10f64.powf(lb),
            n,
            c,
            m,
            eps0_per_s: 10f64.powf(le),
            tm_c: tm,
            tr_c: tr,
        })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    #[test]
    fn cards_round_trip_to_printed_precision(jc in jc_strategy(), beta in 1e-4..0.1f64, m0 in 0.05..1.0f64) {
        let mut case = common::cases().remove(0);
        case.jc = jc;
        case.interface = Interface {
            friction: Friction::PressureDependentShear { m0, beta_per_pa: beta * 1e-6 },
            heat_transfer_w_per_m2_k: 1e8,
        };
        let opts = common::options();
        let prov = common::provenance(&case);
        let input = common::input(&case, &prov, &opts);

        // LS-DYNA: every field fits or the card is comma separated; JC values read back.
        let deck = &render(Dialect::LsDyna, &input).unwrap()[0].contents;
        let cards = check_deck(deck).map_err(TestCaseError::fail)?;
        let num = |s: &str| s.parse::<f64>().unwrap();
        let card2: Vec<f64> = cards[1].iter().map(|s| num(s)).collect();
        let want = [jc.a_pa * 1e-6, jc.b_pa * 1e-6, jc.n, jc.c, jc.m, jc.tm_c + 273.15, jc.tr_c + 273.15, jc.eps0_per_s];
        for (g, w) in card2.iter().zip(want) {
            prop_assert!(close(*g, w, 6), "lsdyna {g} vs {w}");
        }

        // Abaqus: the JC data lines.
        let abq = &render(Dialect::Abaqus, &input).unwrap()[0].contents;
        let after = |key: &str| -> Vec<f64> {
            let l = abq.lines().skip_while(|l| !l.starts_with(key)).find(|l| !l.starts_with('*')).unwrap();
            l.split(',').map(|x| num(x.trim())).collect()
        };
        let plastic = after("*PLASTIC, HARDENING=JOHNSON COOK");
        let want = [jc.a_pa * 1e-6, jc.b_pa * 1e-6, jc.n, jc.m, jc.tm_c + 273.15, jc.tr_c + 273.15];
        for (g, w) in plastic.iter().zip(want) {
            prop_assert!(close(*g, w, 7), "abaqus {g} vs {w}");
        }
        let rate = after("*RATE DEPENDENT");
        prop_assert!(close(rate[0], jc.c, 7) && close(rate[1], jc.eps0_per_s, 7));

        // MatML: the JC parameters, read with quick-xml.
        let xml = &render(Dialect::MatMl, &input).unwrap()[0].contents;
        let read = matml_parameters(xml);
        for (id, w) in [("Initial Yield Stress", jc.a_pa), ("Hardening Constant", jc.b_pa),
                        ("Hardening Exponent", jc.n), ("Strain Rate Constant", jc.c),
                        ("Thermal Softening Exponent", jc.m), ("Melting Temperature", jc.tm_c),
                        ("Reference Temperature", jc.tr_c), ("Reference Strain Rate (/sec)", jc.eps0_per_s),
                        ("Friction Factor m0", m0), ("Pressure Coefficient beta", beta * 1e-6)] {
            prop_assert!(close(read[id], w, 9), "matml {id}: {} vs {w}", read[id]);
        }
    }
}

/// Parameter name (from `ParameterDetails`) -> the first value of its first `ParameterValue`
/// (the workpiece's), read by quick-xml.
fn matml_parameters(xml: &str) -> std::collections::BTreeMap<String, f64> {
    use quick_xml::events::Event;
    let mut r = quick_xml::Reader::from_str(xml);
    let mut by_id = std::collections::BTreeMap::new();
    let mut names = std::collections::BTreeMap::new();
    let mut param: Option<String> = None;
    let mut details: Option<String> = None;
    let mut in_data = false;
    let mut in_name = false;
    loop {
        match r.read_event().unwrap() {
            Event::Start(e) if e.name().as_ref() == b"ParameterDetails" => {
                details = e.try_get_attribute("id").unwrap().map(|a| String::from_utf8(a.value.to_vec()).unwrap());
            }
            Event::End(e) if e.name().as_ref() == b"ParameterDetails" => details = None,
            // The parameter's own Name comes first (unit names follow inside Units): first wins.
            Event::Start(e) if e.name().as_ref() == b"Name" && details.is_some() => in_name = true,
            Event::End(e) if e.name().as_ref() == b"Name" => in_name = false,
            Event::Text(t) if in_name => {
                if let Some(id) = &details {
                    names.entry(id.clone()).or_insert_with(|| t.unescape().unwrap().to_string());
                }
            }
            Event::Start(e) if e.name().as_ref() == b"ParameterValue" => {
                param = e.try_get_attribute("parameter").unwrap().map(|a| String::from_utf8(a.value.to_vec()).unwrap());
            }
            Event::Start(e) if e.name().as_ref() == b"Data" => in_data = true,
            Event::End(e) if e.name().as_ref() == b"Data" => in_data = false,
            Event::End(e) if e.name().as_ref() == b"ParameterValue" => param = None,
            Event::Text(t) if in_data => {
                if let Some(p) = &param {
                    let text = t.unescape().unwrap();
                    if let Ok(v) = text.split(',').next().unwrap_or("").trim().parse::<f64>() {
                        by_id.entry(p.clone()).or_insert(v);
                    }
                }
            }
            Event::Eof => break,
            _ => {}
        }
    }
    by_id.into_iter().filter_map(|(id, v)| names.get(&id).map(|n: &String| (n.clone(), v))).collect()
}

fn assert_all_dialects_fail(case: &common::Case, what: &str) {
    let opts = common::options();
    let prov = common::provenance(case);
    let input = common::input(case, &prov, &opts);
    for d in Dialect::ALL {
        assert!(render(d, &input).is_err(), "{what}: {} rendered", d.name());
    }
    assert!(render_all(&input).is_err());
}

#[test]
fn nan_or_infinity_is_an_error_for_every_dialect() {
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let mut case = common::cases().remove(0);
        case.jc.a_pa = bad;
        assert_all_dialects_fail(&case, "JC A");

        let mut case = common::cases().remove(0);
        case.interface.heat_transfer_w_per_m2_k = bad;
        assert_all_dialects_fail(&case, "heat transfer");

        let mut case = common::cases().remove(0);
        case.interface.friction = Friction::PressureDependentShear { m0: 1.0, beta_per_pa: bad };
        assert_all_dialects_fail(&case, "beta");

        let mut case = common::cases().remove(0);
        case.tool.thermal.conductivity = TempPolynomial::constant(bad);
        assert_all_dialects_fail(&case, "tool conductivity");

        let mut case = common::cases().remove(2);
        if let Some(e) = case.workpiece.elastic.as_mut() {
            e.youngs_pa = bad;
        }
        assert_all_dialects_fail(&case, "Young's modulus");
    }
    // Finite inputs whose derived numbers overflow: A = 1e308 Pa makes A + B eps^n infinite.
    let mut case = common::cases().remove(0);
    case.jc.a_pa = 1e308;
    case.jc.b_pa = 1e308;
    let opts = common::options();
    let prov = common::provenance(&case);
    let err = render(Dialect::Abaqus, &common::input(&case, &prov, &opts)).unwrap_err();
    assert!(matches!(err, ExportError::NonFinite { .. }), "{err}");
}

#[test]
fn nan_options_are_errors() {
    let case = common::cases().remove(0);
    let prov = common::provenance(&case);
    let mut opts = common::options();
    opts.temperatures.step_c = f64::NAN;
    assert!(matches!(render(Dialect::LsDyna, &common::input(&case, &prov, &opts)), Err(ExportError::BadOption { .. })));
    let mut opts = common::options();
    opts.contact_pressures_pa[3] = f64::NAN;
    assert!(render(Dialect::Abaqus, &common::input(&case, &prov, &opts)).is_err());
    let mut opts = common::options();
    opts.tabular_strain_rate_per_s = f64::INFINITY;
    assert!(render(Dialect::Abaqus, &common::input(&case, &prov, &opts)).is_err());
}

#[test]
fn exported_decks_pass_the_column_check() {
    // The snapshot decks themselves, through the same column check as the property test.
    let opts = common::options();
    for case in common::cases() {
        let prov = common::provenance(&case);
        let deck = &render(Dialect::LsDyna, &common::input(&case, &prov, &opts)).unwrap()[0].contents;
        let cards = check_deck(deck).unwrap();
        assert_eq!(cards.len(), 4, "{}: the 4 MAT_015 data cards", case.key);
    }
    // And the check itself rejects a straddling value (fe-cards.md §1.1: `-1.96` shifted by one).
    assert!(dyna_fields("         6     -1.96", 10).is_ok());
    assert!(dyna_fields("         6    -1.960.01", 10).is_err());
}
