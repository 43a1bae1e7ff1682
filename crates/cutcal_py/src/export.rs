//! Export face: FE cards (Abaqus, LS-DYNA, DEFORM-style, MatML; fe-cards.md) rendered by
//! `cutcal_export` with the options and provenance `cutcal export` uses, so a card rendered from
//! Python is byte-identical to the CLI's; files are written with the CLI's atomic writer.

use std::path::{Path, PathBuf};

use cutcal_cli::commands::export::{interface_of, load_tool, standard_options};
use cutcal_export::{render, render_all, Dialect, ExportFile, ExportInput, ExportOptions, Provenance};
use cutcal_export::{TemperatureGrid, UnitSystem};
use cutcal_io::material_file::MaterialFile;
use cutcal_io::output::write_atomic;

use crate::errors::{classify, face, FaceResult};
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
        }
    }
}

fn dialects(format: &str) -> FaceResult<Option<Dialect>> {
    Ok(Some(match format {
        "abaqus" => Dialect::Abaqus,
        "lsdyna" => Dialect::LsDyna,
        "deform" => Dialect::Deform,
        "matml" => Dialect::MatMl,
        "all" => return Ok(None),
        other => {
            return Err(face(anyhow::anyhow!(
                "format must be one of abaqus, lsdyna, deform, matml, all; got {other:?}"
            )))
        }
    }))
}

/// Renders the cards of `req.format` (several files for Abaqus and `all`), nothing written.
pub fn render_cards(mf: &MaterialFile, jc: &NamedJc, req: &ExportRequest) -> FaceResult<Vec<ExportFile>> {
    let dialect = dialects(&req.format)?;
    let units = match req.units.as_str() {
        "tonne-mm-s" => UnitSystem::TonneMmSecondKelvin,
        "si" => UnitSystem::SiKelvin,
        other => return Err(face(anyhow::anyhow!("units must be \"tonne-mm-s\" or \"si\", got {other:?}"))),
    };
    let iface = interface_of(mf).map_err(|e| classify(&e))?;
    let tool = load_tool(mf).map_err(|e| classify(&e))?;
    let wp = &mf.material;
    let options = ExportOptions {
        units,
        temperatures: TemperatureGrid {
            from_c: req.t_from_c.unwrap_or(wp.thermal.valid_from_c),
            to_c: req.t_to_c.unwrap_or(wp.thermal.valid_to_c),
            step_c: req.t_step_c,
        },
        tabular_strain_rate_per_s: req.strain_rate_per_s,
        inelastic_heat_fraction: req.heat_fraction,
        ..standard_options(wp)
    };
    // The CLI's default names the JC file; a set built or identified in Python has none.
    let default_source = match &jc.file_name {
        Some(name) => format!("JC file {name}"),
        None => "JC set given in Python".to_string(),
    };
    let provenance = Provenance {
        cutcal_version: env!("CARGO_PKG_VERSION").to_string(),
        source_test: req.source_test.clone().unwrap_or(default_source),
        model_variant: req.model_variant.clone(),
    };
    let input = ExportInput {
        workpiece: wp,
        jc: &jc.jc,
        tool: tool.as_ref(),
        interface: &iface.interface,
        provenance: &provenance,
        options: &options,
    };
    match dialect {
        Some(d) => render(d, &input),
        None => render_all(&input),
    }
    .map_err(|e| classify(&anyhow::Error::new(e).context(format!("rendering cards for {}", mf.path.display()))))
}

/// Renders and writes the cards into `out` (created if missing), each file atomically; if a write
/// fails, the files of this call are removed. Returns the paths written.
pub fn export_cards(mf: &MaterialFile, jc: &NamedJc, req: &ExportRequest, out: &Path) -> FaceResult<Vec<PathBuf>> {
    let files = render_cards(mf, jc, req)?;
    std::fs::create_dir_all(out).map_err(|e| face(anyhow::anyhow!("cannot create {}: {e}", out.display())))?;
    let mut written: Vec<PathBuf> = Vec::new();
    for f in &files {
        let path = out.join(&f.name);
        if let Err(e) = write_atomic(&path, f.contents.as_bytes()) {
            for p in &written {
                let _ = std::fs::remove_file(p);
            }
            return Err(face(e));
        }
        written.push(path);
    }
    Ok(written)
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
