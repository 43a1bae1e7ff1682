//! Unit tests of `tests_csv`.

use super::*;

fn parse(text: &str) -> Result<Vec<CuttingTest>, InputError> {
    parse_tests(Path::new("t.csv"), text)
}

#[test]
fn reads_c38_fixture_with_units() {
    let p = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/tests/c38.csv");
    let tests = load_tests(&p).unwrap();
    assert_eq!(tests.len(), 5);
    let t3 = &tests[2];
    // Paper Table 2/6: 240 m/min = 4 m/s, 224 N/mm = 224e3 N/m, 0.157 mm.
    assert!((t3.speed_m_per_s - 4.0).abs() < 1e-12);
    assert!((t3.measured.cutting_force_n_per_m.unwrap() - 224e3).abs() < 1e-9);
    assert!((t3.measured.chip_thickness_m.unwrap() - 0.157e-3).abs() < 1e-15);
    assert!(tests[0].measured.cutting_force_n_per_m.is_none());
}

#[test]
fn totals_are_divided_by_width() {
    let t = parse("test,speed_m_min,uncut_mm,width_mm,rake_deg,fc_n,ft_n\n1,200,0.15,1.6,-7,610,450\n").unwrap();
    // 610 N over 1.6 mm = 381.25 N/mm.
    assert!((t[0].measured.cutting_force_n_per_m.unwrap() - 381_250.0).abs() < 1e-6);
}

#[test]
fn errors_are_located() {
    let e = parse("test,speed_m_min,uncut_mm,width_mm,rake_deg,fc_n_per_mm\n1,200,0.15,1.6,0,-5\n").unwrap_err();
    assert_eq!((e.line, e.field.as_str(), e.value.as_str()), (Some(2), "fc_n_per_mm", "-5"));
    let e = parse("test,speed_m_min,uncut_mm,rake_deg\n1,200,0.15,0\n").unwrap_err();
    assert_eq!(e.field, "width_mm");
    let e = parse("test,speed_m_min,uncut_mm,width_mm,rake_deg\n1,200,0.15,1,0\n1,100,0.1,1,0\n").unwrap_err();
    assert_eq!((e.line, e.field.as_str()), (Some(3), "test"));
    let e = parse("test,speed_m_min,uncut_mm,width_mm,rake_deg\n1,NaN,0.15,1,0\n").unwrap_err();
    assert_eq!(e.field, "speed_m_min");
}

#[test]
fn crlf_files_report_the_same_lines() {
    // A spreadsheet export ends its lines with CRLF (csv's own record line is one short there):
    // the bad cell is on line 5 and the short row on line 3 either way.
    for end in ["\n", "\r\n"] {
        let head = "test,speed_m_min,uncut_mm,width_mm,rake_deg,fc_n_per_mm";
        let text = [head, "1,200,0.15,1.6,0,100", "", "# repeat", "2,200,0.15,1.6,0,-5", ""].join(end);
        let e = parse(&text).unwrap_err();
        assert_eq!((e.line, e.field.as_str(), e.value.as_str()), (Some(5), "fc_n_per_mm", "-5"), "{end:?}");
        let text = [head, "1,200,0.15,1.6,0,100", "2,200,0.15", ""].join(end);
        let e = parse(&text).unwrap_err();
        assert_eq!((e.line, e.field.as_str()), (Some(3), "(row)"), "{end:?}");
    }
}

#[test]
fn structure_errors_are_located() {
    let e = parse("test,speed_m_min,uncut_mm,width_mm,rake_deg,uncut_mm\n1,200,0.15,1,0,0.1\n").unwrap_err();
    assert_eq!((e.line, e.field.as_str()), (Some(1), "uncut_mm"));
    assert!(e.reason.contains("duplicate column (column 6)"), "{e}");
    let e = parse("test,speed_m_s,uncut_mm,width_mm,rake_deg\n1,3,0.15,1,0\n").unwrap_err();
    assert!(e.reason.contains("did you mean `speed_m_min`"), "{e}");
    let e = parse("test,speed_m_min,uncut_mm,width_mm,rake_deg\n1,200,0.15,1\n").unwrap_err();
    assert_eq!((e.line, e.field.as_str(), e.value.as_str()), (Some(2), "(row)", "4 cells"));
    let e = parse("# only a comment\n").unwrap_err();
    assert_eq!(e.field, "(header)");
    // A byte-order mark before the header is not part of the first column name.
    assert_eq!(parse("\u{feff}test,speed_m_min,uncut_mm,width_mm,rake_deg\n1,200,0.15,1,0\n").unwrap().len(), 1);
}

#[test]
fn a_missing_measurement_column_names_the_accepted_and_the_found_columns() {
    let text = "# c\ntest,speed_m_min,uncut_mm,width_mm,rake_deg,ft_n_per_mm,chip_mm\n3,240,0.075,1.95,0,186,0.157\n";
    let (_, cols) = parse_tests_with_columns(Path::new("t.csv"), text).unwrap();
    assert_eq!(cols.line, Some(2));
    let all = [MeasuredColumn::CuttingForce, MeasuredColumn::FeedForce, MeasuredColumn::ChipThickness];
    let e = cols.require(Path::new("t.csv"), &all, "X needs Fc").unwrap_err();
    assert_eq!((e.line, e.field.as_str()), (Some(2), "(header)"));
    assert!(e.reason.starts_with("the file has no cutting-force column (accepted names: `fc_n_per_mm`"), "{e}");
    assert!(e.reason.contains("`fc_n` (N, total over the width)"), "{e}");
    assert!(e.reason.contains("columns found: `test`, `speed_m_min`, `uncut_mm`, `width_mm`, `rake_deg`, `ft_n_per_mm`, `chip_mm`; X needs Fc"), "{e}");
    assert!(!e.reason.contains("feed-force"), "{e}");
    // Totals count as well as per-width forces; every missing quantity is named.
    let (_, cols) = parse_tests_with_columns(
        Path::new("t.csv"),
        "test,speed_m_min,uncut_mm,width_mm,rake_deg,fc_n\n1,200,0.15,1.6,-7,610\n",
    )
    .unwrap();
    let e = cols.require(Path::new("t.csv"), &all, "p").unwrap_err();
    assert!(e.reason.contains("no feed-force column") && e.reason.contains(" and no chip-thickness column"), "{e}");
    assert!(cols.require(Path::new("t.csv"), &[MeasuredColumn::CuttingForce], "p").is_ok());
}

#[test]
fn feed_force_too_large_for_the_shear_angle_is_located_at_ft() {
    // C38 test 3 (Table 6) with Ft raised to 600 N/mm: Fc cos(phi) - Ft sin(phi) =
    // 224 cos(25.53 deg) - 600 sin(25.53 deg) = 202.2 - 258.6 < 0.
    let e = parse(
            "test,speed_m_min,uncut_mm,width_mm,rake_deg,fc_n_per_mm,ft_n_per_mm,chip_mm\n3,240,0.075,1.95,0,224,600,0.157\n",
        )
        .unwrap_err();
    assert_eq!((e.line, e.field.as_str(), e.value.as_str()), (Some(2), "ft_n_per_mm", "600"));
    assert!(e.reason.contains("positive shear force"), "{e}");
}

#[test]
fn sd_columns_are_read_in_si() {
    let t = parse(
            "test,speed_m_min,uncut_mm,width_mm,rake_deg,fc_n_per_mm,ft_n_per_mm,fc_sd_n_per_mm,ft_sd_n_per_mm,chip_mm,chip_sd_mm\n\
             1,240,0.075,1.95,0,224,120,3.5,2.25,0.157,0.004\n",
        )
        .unwrap();
    let sd = t[0].measured.sd;
    // 3.5 N/mm = 3500 N/m, 2.25 N/mm = 2250 N/m, 0.004 mm = 4e-6 m.
    assert!((sd.cutting_force_n_per_m.unwrap() - 3500.0).abs() < 1e-9);
    assert!((sd.feed_force_n_per_m.unwrap() - 2250.0).abs() < 1e-9);
    assert!((sd.chip_thickness_m.unwrap() - 4e-6).abs() < 1e-18);
    assert_eq!(sd.interface_temperature_c, None);
}

#[test]
fn an_interface_temperature_sd_is_read_in_kelvin_and_checked() {
    let head = "test,speed_m_min,uncut_mm,width_mm,rake_deg,t_int_c,t_int_sd_c\n";
    let t = parse(&format!("{head}1,240,0.075,1.95,0,612,30.5\n")).unwrap();
    assert_eq!(t[0].measured.sd.interface_temperature_c, Some(30.5));
    for bad in ["0", "-4", "nan", "1e9"] {
        let e = parse(&format!("{head}1,240,0.075,1.95,0,612,{bad}\n")).unwrap_err();
        assert_eq!((e.line, e.field.as_str(), e.value.as_str()), (Some(2), "t_int_sd_c", bad), "{e}");
    }
}

#[test]
fn total_sd_columns_are_divided_by_width() {
    let t = parse("test,speed_m_min,uncut_mm,width_mm,rake_deg,fc_n,fc_sd_n\n1,200,0.15,1.6,-7,610,8\n").unwrap();
    // 8 N over 1.6 mm = 5 N/mm = 5000 N/m.
    assert!((t[0].measured.sd.cutting_force_n_per_m.unwrap() - 5000.0).abs() < 1e-9);
    let e = parse("test,speed_m_min,uncut_mm,width_mm,rake_deg,fc_n,fc_sd_n_per_mm\n1,200,0.15,1.6,-7,610,8\n")
        .unwrap_err();
    assert!(e.reason.contains("not both"), "{e}");
}

#[test]
fn bad_sd_and_flag_cells_are_located() {
    let e = parse("test,speed_m_min,uncut_mm,width_mm,rake_deg,fc_n_per_mm,fc_sd_n_per_mm\n1,200,0.15,1,0,200,-1\n")
        .unwrap_err();
    assert_eq!((e.line, e.field.as_str(), e.value.as_str()), (Some(2), "fc_sd_n_per_mm", "-1"));
    let e =
        parse("test,speed_m_min,uncut_mm,width_mm,rake_deg,chip_mm,chip_sd_mm\n1,200,0.15,1,0,0.3,abc\n").unwrap_err();
    assert_eq!((e.field.as_str(), e.value.as_str()), ("chip_sd_mm", "abc"));
    let e = parse("test,speed_m_min,uncut_mm,width_mm,rake_deg,bue_flag\n1,200,0.15,1,0,2\n").unwrap_err();
    assert_eq!((e.field.as_str(), e.value.as_str()), ("bue_flag", "2"));
}

#[test]
fn repeats_give_the_sd_when_no_column_states_it() {
    // Tests 1-3 repeat one condition: Fc 200, 204, 196 N/mm -> mean 200, sample sd
    // sqrt((0 + 16 + 16) / 2) = 4 N/mm; Ft 100, 100, 103 -> sd sqrt((1 + 1 + 4) / 2) = sqrt(3).
    // Test 4 is another condition (alone): no sd.
    let t = parse(
        "test,speed_m_min,uncut_mm,width_mm,rake_deg,fc_n_per_mm,ft_n_per_mm\n\
             1,200,0.15,1,0,200,100\n2,200,0.15,1,0,204,100\n3,200,0.15,1,0,196,103\n4,300,0.15,1,0,180,90\n",
    )
    .unwrap();
    for r in &t[..3] {
        assert!((r.measured.sd.cutting_force_n_per_m.unwrap() - 4000.0).abs() < 1e-6);
        assert!((r.measured.sd.feed_force_n_per_m.unwrap() - 3f64.sqrt() * 1e3).abs() < 1e-6);
        assert!(r.measured.sd.chip_thickness_m.is_none());
    }
    assert_eq!(t[3].measured.sd, MeasuredSd::default());
    // With an sd column the column wins, and the repeats do not fill that quantity.
    let t = parse(
            "test,speed_m_min,uncut_mm,width_mm,rake_deg,fc_n_per_mm,fc_sd_n_per_mm\n1,200,0.15,1,0,200,1\n2,200,0.15,1,0,204,\n",
        )
        .unwrap();
    assert!((t[0].measured.sd.cutting_force_n_per_m.unwrap() - 1000.0).abs() < 1e-9);
    assert!(t[1].measured.sd.cutting_force_n_per_m.is_none());
}
