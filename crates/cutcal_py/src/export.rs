//! Export face: FE cards (Abaqus, LS-DYNA, DEFORM-style, MatML; fe-cards.md) rendered by
//! `cutcal_report::export::render_request`, the function `cutcal export` calls, so a card rendered
//! from Python is byte-identical to the CLI's; files are written by the same atomic writer.

use std::path::{Path, PathBuf};

use cutcal_export::ExportFile;
use cutcal_io::material_file::MaterialFile;
use cutcal_report::export::{render_request, write_files, ExportRequest as LibRequest, FormatChoice, UnitsChoice};

use crate::errors::{face, FaceResult};
use crate::types::NamedJc;

/// Options of an export; the defaults are the CLI's (`cutcal export --help`).
#[derive(Debug, Clone, PartialEq)]
pub struct ExportRequest {
    /// `abaqus`, `lsdyna`, `deform`, `matml` or `all`.
    pub format: String,
    /// `tonne-mm-s` or `si`.
    pub units: String,
    /// Lowest table temperature, degC (default: the workpiece's validity range start).
    pub t_from_c: Option<f64>,
    /// Highest table temperature, degC (default: the validity range end).
    pub t_to_c: Option<f64>,
    /// Table temperature step, degC.
    pub t_step_c: f64,
    /// Strain rate of the tabular Abaqus variant, 1/s.
    pub strain_rate_per_s: f64,
    /// Taylor-Quinney fraction.
    pub heat_fraction: f64,
    /// Source test named in the headers (default: `JC file <name>` as the CLI writes, or
    /// `JC set given in Python` for a set not read from a file).
    pub source_test: Option<String>,
    /// Model variant named in the headers.
    pub model_variant: String,
    /// Tool-chip contact temperature of the LS-DYNA FS = 2 friction table, degC (the CLI's
    /// `--contact-temperature-c`; default: the homologous temperature 0.5 of the set, stated).
    pub contact_temperature_c: Option<f64>,
    /// Cutting speed, m/min, for the LS-DYNA termination time (the CLI's `--cutting-speed-m-min`;
    /// default: none, no termination card).
    pub cutting_speed_m_per_min: Option<f64>,
}

impl Default for ExportRequest {
    fn default() -> Self {
        Self {
            format: "all".into(),
            units: "tonne-mm-s".into(),
            t_from_c: None,
            t_to_c: None,
            t_step_c: 100.0,
            strain_rate_per_s: 1e4,
            heat_fraction: 0.9,
            source_test: None,
            model_variant: "as identified in the JC file".into(),
            contact_temperature_c: None,
            cutting_speed_m_per_min: None,
        }
    }
}

fn format_choice(format: &str) -> FaceResult<FormatChoice> {
    Ok(match format {
        "abaqus" => FormatChoice::Abaqus,
        "lsdyna" => FormatChoice::Lsdyna,
        "deform" => FormatChoice::Deform,
        "matml" => FormatChoice::Matml,
        "all" => FormatChoice::All,
        other => {
            return Err(face(anyhow::anyhow!(
                "format must be one of abaqus, lsdyna, deform, matml, all; got {other:?}"
            )))
        }
    })
}

/// The library request (`cutcal export`'s) of a Python request.
fn library_request(req: &ExportRequest) -> FaceResult<LibRequest> {
    let units = match req.units.as_str() {
        "tonne-mm-s" => UnitsChoice::TonneMmS,
        "si" => UnitsChoice::Si,
        other => return Err(face(anyhow::anyhow!("units must be \"tonne-mm-s\" or \"si\", got {other:?}"))),
    };
    Ok(LibRequest {
        format: format_choice(&req.format)?,
        units,
        t_from_c: req.t_from_c,
        t_to_c: req.t_to_c,
        t_step_c: req.t_step_c,
        strain_rate: req.strain_rate_per_s,
        heat_fraction: req.heat_fraction,
        source_test: req.source_test.clone(),
        model_variant: req.model_variant.clone(),
        contact_temperature_c: req.contact_temperature_c,
        cutting_speed_m_min: req.cutting_speed_m_per_min,
        tests: None,
        test: None,
    })
}

/// Renders the cards of `req.format` (several files for Abaqus and `all`), nothing written.
pub fn render_cards(mf: &MaterialFile, jc: &NamedJc, req: &ExportRequest) -> FaceResult<Vec<ExportFile>> {
    let lib = library_request(req)?;
    // The CLI's default names the JC file; a set built or identified in Python has none.
    let default_source = match &jc.file_name {
        Some(name) => format!("JC file {name}"),
        None => "JC set given in Python".to_string(),
    };
    let what = || format!("rendering cards for {}", mf.path.display());
    render_request(mf, &jc.jc, default_source, &lib, &what).map_err(face)
}

/// Renders and writes the cards into `out` (created if missing), each file atomically; if a write
/// fails, the files of this call are removed. Returns the paths written.
pub fn export_cards(mf: &MaterialFile, jc: &NamedJc, req: &ExportRequest, out: &Path) -> FaceResult<Vec<PathBuf>> {
    let files = render_cards(mf, jc, req)?;
    write_files(out, &files).map_err(face)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::types::{jc_from_file, material_from_file};

    #[test]
    fn renders_table5_into_the_lsdyna_deck_and_writes_all_dialects() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
        let mf = material_from_file(&root.join("fixtures/materials/c38.toml")).unwrap();
        let jc = jc_from_file(&root.join("fixtures/jc/c38_table5.toml")).unwrap();
        let req = ExportRequest { format: "lsdyna".into(), ..Default::default() };
        let files = render_cards(&mf, &jc, &req).unwrap();
        assert_eq!(files.len(), 1);
        // Table 5 (paper): A = 589 MPa, B = 145, n = 0.25, C = 0.069, m = 1.1 on MAT_015 card 2.
        assert!(files[0].contents.contains("      589.      145.      0.25     0.069       1.1"));
        assert!(files[0].contents.contains("JC file c38_table5.toml"));
        let dir = tempfile::tempdir().unwrap();
        let written = export_cards(&mf, &jc, &ExportRequest::default(), dir.path()).unwrap();
        assert_eq!(written.len(), 7);
        let bad = ExportRequest { format: "ansys".into(), ..Default::default() };
        assert!(render_cards(&mf, &jc, &bad).unwrap_err().message.contains("ansys"));
    }
}
