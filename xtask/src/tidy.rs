//! Tidy checks run as a test: file headers, fixture provenance, trailing whitespace, templates used.
//! Each failure prints `path:line` and the fix.

#[cfg(test)]
mod tests {
    use std::fs;
    use std::path::{Path, PathBuf};

    fn root() -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
    }

    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        let Ok(entries) = fs::read_dir(dir) else { return };
        for e in entries.flatten() {
            let p = e.path();
            let name = p.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
            if name.starts_with('.') || name.starts_with("target") || name == "fuzz" {
                continue;
            }
            if p.is_dir() {
                walk(&p, out);
            } else {
                out.push(p);
            }
        }
    }

    fn files(sub: &str, ext: &[&str]) -> Vec<PathBuf> {
        let mut v = Vec::new();
        walk(&root().join(sub), &mut v);
        v.retain(|p| p.extension().is_some_and(|e| ext.iter().any(|x| e == *x)));
        v.sort();
        v
    }

    #[test]
    fn every_rust_file_starts_with_a_module_doc() {
        let mut bad = Vec::new();
        for dir in ["crates", "xtask", "tests"] {
            for f in files(dir, &["rs"]) {
                let text = fs::read_to_string(&f).unwrap_or_default();
                if !text.trim_start().starts_with("//!") {
                    bad.push(format!("{}:1: start the file with a `//!` line saying what it holds", f.display()));
                }
            }
        }
        assert!(bad.is_empty(), "\n{}", bad.join("\n"));
    }

    #[test]
    fn no_trailing_whitespace() {
        let mut bad = Vec::new();
        for dir in ["crates", "xtask", "tests", "fixtures", "templates", "docs"] {
            for f in files(dir, &["rs", "toml", "md", "csv", "hbs"]) {
                let text = fs::read_to_string(&f).unwrap_or_default();
                for (i, l) in text.lines().enumerate() {
                    if l.ends_with(' ') || l.ends_with('\t') {
                        bad.push(format!("{}:{}: remove the trailing whitespace", f.display(), i + 1));
                    }
                }
            }
        }
        assert!(bad.is_empty(), "\n{}", bad.join("\n"));
    }

    #[test]
    fn every_fixture_states_its_source() {
        let mut bad = Vec::new();
        let readme = fs::read_to_string(root().join("fixtures/README.md")).unwrap_or_default();
        for f in files("fixtures", &["toml", "csv"]) {
            let rel = f.strip_prefix(root().join("fixtures")).unwrap_or(&f).to_string_lossy().replace('\\', "/");
            let text = fs::read_to_string(&f).unwrap_or_default();
            let commented = text.lines().next().is_some_and(|l| l.starts_with('#'));
            let dir = rel.split('/').next().unwrap_or("");
            let name = f.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
            let local =
                f.parent().map(|d| fs::read_to_string(d.join("README.md")).unwrap_or_default()).unwrap_or_default();
            if !commented && !readme.contains(&rel) && !readme.contains(&format!("`{dir}/")) && !local.contains(&name) {
                bad.push(format!("fixtures/{rel}:1: start with a `#` line naming the source, or list it in fixtures/README.md or a README.md beside it"));
            }
        }
        assert!(bad.is_empty(), "\n{}", bad.join("\n"));
    }

    #[test]
    fn every_template_is_used_by_the_exporters() {
        let mut src = String::new();
        for f in files("crates/cutcal_export", &["rs"]) {
            src.push_str(&fs::read_to_string(&f).unwrap_or_default());
        }
        let mut bad = Vec::new();
        for t in files("templates", &["hbs", "tpl", "txt", "f", "xml"]) {
            let name = t.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
            if !src.contains(&name) {
                bad.push(format!(
                    "{}: not referenced by cutcal_export (render it in a snapshot or delete it)",
                    t.display()
                ));
            }
        }
        assert!(bad.is_empty(), "\n{}", bad.join("\n"));
    }
}
