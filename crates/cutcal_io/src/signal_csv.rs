//! Streaming reader of a dynamometer signal CSV (`<test>.csv`): a time column and force columns.
//!
//! Lines before the header (comments, acquisition metadata) are skipped: the header is the first
//! line that holds the time column's name. Columns are `time_s`, `fc_n`, `ft_n` and optional
//! `fp_n`, or other names mapped with `--channels fc=Fz,ft=Fx,fp=Fy` (and `time=...`). Separators
//! `,` `;` or tab. An empty or `NaN` cell is a dropout (the sample keeps its time, adds nothing);
//! anything else that is not a number is a located error. Samples go straight into a
//! [`cutcal_signal::Reducer`]: memory does not grow with the file.

use std::fs::File;
use std::io::{BufRead, BufReader};
use std::path::Path;

use cutcal_signal::{Reduced, Reducer, SignalError, DEFAULT_MAX_BLOCKS};

use super::InputError;

/// Column names of the channels in a signal file.
#[derive(Debug, Clone, PartialEq)]
pub struct ChannelMap {
    /// Time column, s.
    pub time: String,
    /// Cutting force column, N.
    pub fc: String,
    /// Feed (thrust) force column, N.
    pub ft: String,
    /// Passive force column, N (optional in the file).
    pub fp: String,
}

impl Default for ChannelMap {
    fn default() -> Self {
        ChannelMap { time: "time_s".into(), fc: "fc_n".into(), ft: "ft_n".into(), fp: "fp_n".into() }
    }
}

impl ChannelMap {
    /// Parses `fc=Fz,ft=Fx,fp=Fy[,time=t]` over the defaults.
    pub fn parse(spec: &str) -> Result<Self, String> {
        let mut m = ChannelMap::default();
        for part in spec.split(',').map(str::trim).filter(|p| !p.is_empty()) {
            let (k, v) = part.split_once('=').ok_or_else(|| format!("`{part}`: expected key=column, e.g. fc=Fz"))?;
            let v = v.trim().to_string();
            match k.trim() {
                "fc" => m.fc = v,
                "ft" => m.ft = v,
                "fp" => m.fp = v,
                "time" => m.time = v,
                other => return Err(format!("`{other}`: unknown channel (expected fc, ft, fp or time)")),
            }
        }
        Ok(m)
    }
}

/// A reduced signal and whether the passive force was present (channel 2).
#[derive(Debug, Clone)]
pub struct SignalFile {
    /// Reduced channels `[fc, ft, fp]` (fp is NaN-free zeros when absent).
    pub reduced: Reduced,
    /// True when the file has the passive-force column.
    pub has_fp: bool,
}

fn split(line: &str) -> Vec<&str> {
    let sep = if line.contains(',') {
        ','
    } else if line.contains(';') {
        ';'
    } else {
        '\t'
    };
    line.split(sep).map(|s| s.trim().trim_matches('"')).collect()
}

/// Reads and reduces a signal file; `progress` is called with the bytes read so far.
pub fn read_signal(path: &Path, map: &ChannelMap, mut progress: impl FnMut(u64)) -> Result<SignalFile, InputError> {
    let f = File::open(path).map_err(|e| InputError::new(path, None, "(file)", "", format!("cannot read: {e}")))?;
    let mut rdr = BufReader::with_capacity(1 << 16, f);
    let mut line = String::new();
    let mut line_no = 0usize;
    let mut bytes = 0u64;
    // Header: the first line naming the time column.
    let cols: Vec<String> = loop {
        line.clear();
        let n = rdr
            .read_line(&mut line)
            .map_err(|e| InputError::new(path, Some(line_no + 1), "(line)", "", format!("cannot read: {e}")))?;
        if n == 0 {
            return Err(InputError::new(
                path,
                None,
                &map.time,
                "",
                format!(
                    "no header line naming the time column `{}` (use --channels time=<name> for another name)",
                    map.time
                ),
            ));
        }
        bytes += n as u64;
        line_no += 1;
        let l = line.trim_start_matches('\u{feff}').trim();
        if l.starts_with('#') {
            continue;
        }
        let cells = split(l);
        if cells.iter().any(|c| *c == map.time) {
            break cells.into_iter().map(String::from).collect();
        }
    };
    let header_line = line_no;
    let find = |name: &str, required: bool| -> Result<Option<usize>, InputError> {
        match cols.iter().position(|c| c == name) {
            Some(i) => Ok(Some(i)),
            None if required => Err(InputError::new(
                path,
                Some(header_line),
                name,
                "",
                format!("column missing; the header has {cols:?} (map other names with --channels fc=..,ft=..,fp=..)"),
            )),
            None => Ok(None),
        }
    };
    let it = find(&map.time, true)?.unwrap_or_default();
    let ic = find(&map.fc, true)?.unwrap_or_default();
    let ift = find(&map.ft, true)?.unwrap_or_default();
    let ip = find(&map.fp, false)?;
    let mut reducer =
        Reducer::new(3, DEFAULT_MAX_BLOCKS).map_err(|e| InputError::new(path, None, "(signal)", "", e.to_string()))?;
    let mut values = [0.0f64; 3];
    loop {
        line.clear();
        let n = rdr
            .read_line(&mut line)
            .map_err(|e| InputError::new(path, Some(line_no + 1), "(line)", "", format!("cannot read: {e}")))?;
        if n == 0 {
            break;
        }
        bytes += n as u64;
        line_no += 1;
        let l = line.trim();
        if l.is_empty() || l.starts_with('#') {
            continue;
        }
        let cells = split(l);
        if cells.len() != cols.len() {
            return Err(InputError::new(
                path,
                Some(line_no),
                "(row)",
                format!("{} cells", cells.len()),
                format!("the header (line {header_line}) has {} columns", cols.len()),
            ));
        }
        let num = |i: usize, name: &str, dropout_ok: bool| -> Result<f64, InputError> {
            let s = cells[i];
            if dropout_ok && (s.is_empty() || s.eq_ignore_ascii_case("nan")) {
                return Ok(f64::NAN);
            }
            match s.parse::<f64>() {
                Ok(v) if v.is_finite() => Ok(v),
                _ => Err(InputError::new(path, Some(line_no), name, s, "not a finite number")),
            }
        };
        let t = num(it, &map.time, false)?;
        values[0] = num(ic, &map.fc, true)?;
        values[1] = num(ift, &map.ft, true)?;
        values[2] = match ip {
            Some(i) => num(i, &map.fp, true)?,
            None => 0.0,
        };
        reducer.push(t, &values).map_err(|e| match e {
            SignalError::TimeNotIncreasing { previous_s, .. } => InputError::new(
                path,
                Some(line_no),
                &map.time,
                cells[it],
                format!("time must increase (previous sample {previous_s} s)"),
            ),
            other => InputError::new(path, Some(line_no), "(row)", "", other.to_string()),
        })?;
        if line_no.is_multiple_of(65_536) {
            progress(bytes);
        }
    }
    progress(bytes);
    let reduced = reducer.finish().map_err(|e| InputError::new(path, None, "(signal)", "", e.to_string()))?;
    Ok(SignalFile { reduced, has_fp: ip.is_some() })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Write;

    #[test]
    fn skips_metadata_maps_channels_and_locates_errors() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("s.csv");
        let mut f = File::create(&p).unwrap();
        writeln!(f, "Kistler export v2\nrate;10000\nt;Fx;Fy;Fz").unwrap();
        for i in 0..2000 {
            writeln!(f, "{};{};{};{}", i as f64 * 1e-4, 30.0, 5.0, 50.0).unwrap();
        }
        drop(f);
        let map = ChannelMap::parse("fc=Fz,ft=Fx,fp=Fy,time=t").unwrap();
        let s = read_signal(&p, &map, |_| {}).unwrap();
        assert!(s.has_fp);
        assert_eq!(s.reduced.samples, 2000);
        assert!((s.reduced.blocks[0][0].moments.mean - 50.0).abs() < 1e-12);
        let e = read_signal(&p, &ChannelMap::default(), |_| {}).unwrap_err();
        assert_eq!(e.field, "time_s");
        std::fs::write(&p, "time_s,fc_n,ft_n\n0,1,2\n0.001,x,2\n").unwrap();
        let e = read_signal(&p, &ChannelMap::default(), |_| {}).unwrap_err();
        assert_eq!((e.line, e.field.as_str(), e.value.as_str()), (Some(3), "fc_n", "x"));
        std::fs::write(&p, "time_s,fc_n,ft_n\n0,1,2\n0,1,2\n").unwrap();
        let e = read_signal(&p, &ChannelMap::default(), |_| {}).unwrap_err();
        assert_eq!((e.line, e.field.as_str()), (Some(3), "time_s"));
    }
}
