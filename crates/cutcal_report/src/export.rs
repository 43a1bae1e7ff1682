//! Exports (`cutcal export`, `cutcal run`, Python's `export`/`render`): FE cards (Abaqus, LS-DYNA, DEFORM-style, MatML) from a material file and a JC
//! file, rendered by `cutcal_export` and written atomically (issue 4; fe-cards.md).
//!
//! The tool material is read from `<tool>.toml` beside the workpiece file when the workpiece's
//! `[interface]` names one. Everything is rendered before anything is written; each file is written
//! to a temporary sibling and renamed, and if any write fails the files of this run are removed.

use std::path::{Path, PathBuf};

use cutcal_export::{
    render, render_all, render_cut2d, ContactTemperature, Dialect, ExportFile, ExportInput, ExportOptions, Provenance,
    TemperatureGrid, UnitSystem, STANDARD_CONTACT_PRESSURES_MPA, STANDARD_FLOW_STRAIN_RATES_PER_S,
    STANDARD_PLASTIC_STRAINS,
};

use cutcal_io::jc_file::load_jc;
use cutcal_io::tests_csv::load_tests;
use cutcal_model::{JcParams, Material};

use cutcal_io::material_file::{load_material, InterfaceSection, MaterialFile};
use cutcal_io::output::write_atomic;

use crate::bail;
use crate::error::{Context, Result};

/// Which cards to write.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
pub enum FormatChoice {
    /// Abaqus: native JC, tabular *PLASTIC variant, VFRIC source for Eq 17.
    Abaqus,
    /// LS-DYNA keyword deck.
    Lsdyna,
    /// DEFORM-style KEY block and readable sheet (unverified format).
    Deform,
    /// MatML 3.1 XML.
    Matml,
    /// Every dialect.
    All,
}

/// Unit system of the Abaqus and LS-DYNA cards.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
pub enum UnitsChoice {
    /// tonne, mm, s, N, MPa, mJ, K.
    TonneMmS,
    /// kg, m, s, N, Pa, J, K.
    Si,
}

/// Options of an export (the CLI's `export` flags, Python's keywords); the defaults are the CLI's.
#[derive(Debug, Clone, PartialEq)]
pub struct ExportRequest {
    /// Which cards to write.
    pub format: FormatChoice,
    /// Unit system of the Abaqus and LS-DYNA cards.
    pub units: UnitsChoice,
    /// Lowest table temperature, degC (default: the workpiece's validity range start).
    pub t_from_c: Option<f64>,
    /// Highest table temperature, degC (default: the workpiece's validity range end).
    pub t_to_c: Option<f64>,
    /// Table temperature step, degC.
    pub t_step_c: f64,
    /// Strain rate of the tabular Abaqus *PLASTIC variant, 1/s.
    pub strain_rate: f64,
    /// Fraction of plastic work converted to heat (Taylor-Quinney; not given in the paper).
    pub heat_fraction: f64,
    /// Source test named in the headers (default: the JC file name).
    pub source_test: Option<String>,
    /// Model variant named in the headers.
    pub model_variant: String,
    /// Tool-chip contact temperature, degC, of the LS-DYNA FS = 2 friction table (default: the
    /// homologous temperature 0.5 of the JC set, stated in the deck).
    pub contact_temperature_c: Option<f64>,
    /// Cutting speed, m/min: the LS-DYNA deck then gets *CONTROL_TERMINATION (paper Sec 5.1).
    pub cutting_speed_m_min: Option<f64>,
    /// Cutting tests (CSV): one complete 2-D LS-DYNA deck per test (lsdyna or all only).
    pub tests: Option<PathBuf>,
    /// Only this test of `tests`.
    pub test: Option<String>,
}

impl Default for ExportRequest {
    fn default() -> Self {
        Self {
            format: FormatChoice::All,
            units: UnitsChoice::TonneMmS,
            t_from_c: None,
            t_to_c: None,
            t_step_c: 100.0,
            strain_rate: 1e4,
            heat_fraction: 0.9,
            source_test: None,
            model_variant: "as identified in the JC file".into(),
            contact_temperature_c: None,
            cutting_speed_m_min: None,
            tests: None,
            test: None,
        }
    }
}

/// The interface section of a workpiece file, or a located error.
pub fn interface_of(wp_file: &MaterialFile) -> Result<&InterfaceSection> {
    wp_file.interface.as_ref().with_context(|| {
        format!(
            "{}: no [interface] section (friction and heat transfer are needed by the cards)",
            wp_file.path.display()
        )
    })
}

/// The tool material named by `[interface].tool`, read from `<tool>.toml` beside the workpiece file.
pub fn load_tool(wp_file: &MaterialFile) -> Result<Option<Material>> {
    match wp_file.interface.as_ref().and_then(|i| i.tool.as_ref()) {
        Some(name) => {
            let dir = wp_file.path.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
            let path = dir.join(format!("{name}.toml"));
            Ok(Some(
                load_material(&path)
                    .with_context(|| format!("reading the tool material named by [interface].tool = {name:?}"))?
                    .material,
            ))
        }
        None => Ok(None),
    }
}

/// The default export options of a workpiece: its thermal range every 100 K, the standard strain
/// and pressure grids, 1e4 1/s for the tabular card, heat fraction 0.9, the default contact
/// temperature (homologous 0.5, stated in the deck) and no cutting speed (no termination card).
#[must_use]
pub fn standard_options(wp: &Material) -> ExportOptions {
    ExportOptions {
        units: UnitSystem::TonneMmSecondKelvin,
        temperatures: TemperatureGrid { from_c: wp.thermal.valid_from_c, to_c: wp.thermal.valid_to_c, step_c: 100.0 },
        plastic_strains: STANDARD_PLASTIC_STRAINS.to_vec(),
        tabular_strain_rate_per_s: 1e4,
        flow_strain_rates_per_s: STANDARD_FLOW_STRAIN_RATES_PER_S.to_vec(),
        contact_pressures_pa: STANDARD_CONTACT_PRESSURES_MPA.iter().map(|p| p * 1e6).collect(),
        inelastic_heat_fraction: 0.9,
        contact_temperature: None,
        cutting_speed_m_per_s: None,
    }
}

/// Every card of every dialect for a workpiece file and a JC set, with the standard options.
pub fn render_cards(wp_file: &MaterialFile, jc: &JcParams, provenance: &Provenance) -> Result<Vec<ExportFile>> {
    let iface = interface_of(wp_file)?;
    let tool = load_tool(wp_file)?;
    let options = standard_options(&wp_file.material);
    let input = ExportInput {
        workpiece: &wp_file.material,
        jc,
        tool: tool.as_ref(),
        interface: &iface.interface,
        provenance,
        options: &options,
    };
    render_all(&input).with_context(|| format!("rendering cards for {}", wp_file.path.display()))
}

/// The export options of a request for the workpiece `wp`.
#[must_use]
pub fn export_options(wp: &Material, args: &ExportRequest) -> ExportOptions {
    let options = ExportOptions {
        units: match args.units {
            UnitsChoice::TonneMmS => UnitSystem::TonneMmSecondKelvin,
            UnitsChoice::Si => UnitSystem::SiKelvin,
        },
        temperatures: TemperatureGrid {
            from_c: args.t_from_c.unwrap_or(wp.thermal.valid_from_c),
            to_c: args.t_to_c.unwrap_or(wp.thermal.valid_to_c),
            step_c: args.t_step_c,
        },
        ..standard_options(wp)
    };
    ExportOptions {
        tabular_strain_rate_per_s: args.strain_rate,
        inelastic_heat_fraction: args.heat_fraction,
        contact_temperature: args
            .contact_temperature_c
            .map(|t| ContactTemperature { temp_c: t, source: "given by --contact-temperature-c".into() }),
        cutting_speed_m_per_s: args.cutting_speed_m_min.map(|v| v / 60.0),
        ..options
    }
}

/// Renders the cards of a request (and the 2-D decks of its tests) for the workpiece file `wp_file`
/// and the JC set `jc`; `default_source` names the JC set in the headers unless the request names
/// a source test, `what` is the context of a render error. Nothing is written.
///
/// Returns an error if the interface or the tool is missing, an option is refused by the
/// exporters, or a deck's test is not there.
pub fn render_request(
    wp_file: &MaterialFile,
    jc: &JcParams,
    default_source: String,
    args: &ExportRequest,
    what: &dyn Fn() -> String,
) -> Result<Vec<ExportFile>> {
    let iface = interface_of(wp_file)?;
    let tool = load_tool(wp_file)?;
    let wp = &wp_file.material;
    let options = export_options(wp, args);
    let provenance = Provenance {
        cutcal_version: env!("CARGO_PKG_VERSION").to_string(),
        source_test: args.source_test.clone().unwrap_or(default_source),
        model_variant: args.model_variant.clone(),
    };
    let input = ExportInput {
        workpiece: wp,
        jc,
        tool: tool.as_ref(),
        interface: &iface.interface,
        provenance: &provenance,
        options: &options,
    };
    let mut files = match args.format {
        FormatChoice::Abaqus => render(Dialect::Abaqus, &input),
        FormatChoice::Lsdyna => render(Dialect::LsDyna, &input),
        FormatChoice::Deform => render(Dialect::Deform, &input),
        FormatChoice::Matml => render(Dialect::MatMl, &input),
        FormatChoice::All => render_all(&input),
    }
    .with_context(what)?;
    files.extend(decks(args, &input)?);
    Ok(files)
}

/// Writes `files` into `out` (created if missing), each atomically; if a write fails, the files
/// of this call are removed. Returns the paths written.
pub fn write_files(out: &Path, files: &[ExportFile]) -> Result<Vec<PathBuf>> {
    if files.is_empty() {
        bail!("no cards were rendered");
    }
    std::fs::create_dir_all(out).with_context(|| format!("cannot create {}", out.display()))?;
    let mut written: Vec<PathBuf> = Vec::new();
    for f in files {
        let path = out.join(&f.name);
        if let Err(e) = write_atomic(&path, f.contents.as_bytes()) {
            for p in &written {
                let _ = std::fs::remove_file(p);
            }
            return Err(e.into());
        }
        written.push(path);
    }
    Ok(written)
}

/// What `cutcal export` does: reads the workpiece and the JC file, renders every card asked for
/// (everything before anything is written) and writes them into `out`. Returns the paths written.
///
/// Returns an error if an input file cannot be read or validated, the interface or tool is
/// missing, a card cannot be rendered, or a file cannot be written (then no file of this run is
/// left behind).
pub fn export_files(material: &Path, jc_path: &Path, out: &Path, args: &ExportRequest) -> Result<Vec<PathBuf>> {
    let wp_file = load_material(material)?;
    let jc = load_jc(jc_path)?;
    let jc_name = jc_path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    let what = || format!("rendering cards for {} with {}", material.display(), jc_path.display());
    let files = render_request(&wp_file, &jc, format!("JC file {jc_name}"), args, &what)?;
    write_files(out, &files)
}

/// The complete 2-D decks of `--tests` (all, or `--test`), or none without `--tests`.
fn decks(args: &ExportRequest, input: &ExportInput<'_>) -> Result<Vec<ExportFile>> {
    let Some(path) = &args.tests else { return Ok(Vec::new()) };
    if !matches!(args.format, FormatChoice::Lsdyna | FormatChoice::All) {
        bail!("--tests writes LS-DYNA decks: use it with --format lsdyna or all");
    }
    let tests = load_tests(path)?;
    let chosen: Vec<_> = tests.iter().filter(|t| args.test.as_ref().is_none_or(|id| &t.id == id)).collect();
    if chosen.is_empty() {
        bail!("{}: no test {:?}", path.display(), args.test.as_deref().unwrap_or(""));
    }
    chosen
        .into_iter()
        .map(|t| {
            render_cut2d(input, t)
                .with_context(|| format!("rendering the 2-D deck of test {} of {}", t.id, path.display()))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fixture(rel: &str) -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../..").join(rel)
    }

    struct Job {
        material: PathBuf,
        jc: PathBuf,
        out: PathBuf,
        req: ExportRequest,
    }

    fn args(material: &str, jc: &str, out: &Path) -> Job {
        let req = ExportRequest { model_variant: "enhanced DPZD".into(), ..Default::default() };
        Job { material: fixture(material), jc: fixture(jc), out: out.to_path_buf(), req }
    }

    fn run(j: &Job) -> Result<Vec<PathBuf>> {
        export_files(&j.material, &j.jc, &j.out, &j.req)
    }

    #[test]
    fn tests_option_writes_one_deck_per_chosen_test() {
        let dir = tempfile::tempdir().unwrap();
        let mut a = args("fixtures/materials/c38.toml", "fixtures/jc/c38_table5.toml", dir.path());
        a.req.format = FormatChoice::Lsdyna;
        a.req.tests = Some(fixture("fixtures/tests/c38.csv"));
        a.req.test = Some("3".into());
        run(&a).unwrap();
        let deck = std::fs::read_to_string(dir.path().join("c38_cut2d_3.k")).unwrap();
        // C38 test 3 (paper Table 2): 240 m/min, 0.075 mm; edge radius 25 um (fixtures/tests/c38.csv).
        assert!(
            deck.contains("V = 240. m/min, t1 = 0.075 mm") && deck.contains("edge radius = 25. um"),
            "{}",
            &deck[..2000]
        );
        assert!(dir.path().join("c38_lsdyna.k").exists());
        assert!(!dir.path().join("c38_cut2d_1.k").exists());

        a.req.test = Some("9".into());
        let err = run(&a).unwrap_err();
        assert!(err.chain_text().contains("no test \"9\""), "{}", err.chain_text());
        a.req.test = None;
        a.req.format = FormatChoice::Matml;
        assert!(run(&a).unwrap_err().chain_text().contains("--format lsdyna or all"));
    }

    #[test]
    fn export_all_writes_every_dialect_with_the_tool() {
        let dir = tempfile::tempdir().unwrap();
        run(&args("fixtures/materials/c38.toml", "fixtures/jc/c38_table5.toml", dir.path())).unwrap();
        let mut names: Vec<String> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        assert_eq!(
            names,
            [
                "c38_abaqus_jc.inp",
                "c38_abaqus_tabular.inp",
                "c38_abaqus_vfriction.f",
                "c38_deform.key",
                "c38_deform_sheet.txt",
                "c38_lsdyna.k",
                "c38_matml.xml"
            ]
        );
        let deck = std::fs::read_to_string(dir.path().join("c38_lsdyna.k")).unwrap();
        // Table 5 (paper): A = 589 MPa on MAT_015 card 2; the H13A tool part comes from h13a.toml.
        assert!(deck.contains("      589.      145.      0.25     0.069       1.1"));
        assert!(deck.contains("H13A tool"));
    }

    #[test]
    fn a_failed_render_writes_nothing() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("cards");
        let mut a = args("fixtures/materials/c38.toml", "fixtures/jc/c38_table5.toml", &out);
        a.req.t_step_c = -5.0;
        let err = run(&a).unwrap_err();
        assert!(err.chain_text().contains("temperatures"), "{}", err.chain_text());
        assert!(!out.exists() || std::fs::read_dir(&out).unwrap().next().is_none());
    }

    #[test]
    fn contact_temperature_and_speed_reach_the_lsdyna_deck() {
        let dir = tempfile::tempdir().unwrap();
        let mut a = args("fixtures/materials/c38.toml", "fixtures/jc/c38_table5.toml", dir.path());
        a.req.format = FormatChoice::Lsdyna;
        a.req.contact_temperature_c = Some(600.0);
        a.req.cutting_speed_m_min = Some(180.0);
        run(&a).unwrap();
        let deck = std::fs::read_to_string(dir.path().join("c38_lsdyna.k")).unwrap();
        // k(600 degC) of the C38 Table 5 set at eps = 2, epsdot = 1e4 1/s: 454.5733 MPa (python:
        // (589+145*2**0.25)*(1+0.069*math.log(1e4))*(1-(580/1440)**1.1)/3**0.5); VC = m0 k, m0 = 1.
        assert!(deck.contains("Tc = 600. degC") && deck.contains("   454.573 "), "{deck}");
        // ENDTIM = 8 mm / (180 m/min) = 8e-3 / 3 s.
        assert!(deck.contains("*CONTROL_TERMINATION") && deck.contains("ENDTIM = 0.002666667"), "{deck}");

        a.req.contact_temperature_c = Some(1500.0);
        let err = run(&a).unwrap_err();
        assert!(err.chain_text().contains("contact_temperature_c"), "{}", err.chain_text());
    }
}
