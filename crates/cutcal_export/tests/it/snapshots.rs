//! Snapshots `{dialect}_{material}` of every dialect for C38, 42CrMo4 and AA6082 with the paper's
//! Table 5 JC sets (style.md §13). The cutcal version is filtered so snapshots are stable.

use cutcal_export::{render, Dialect};

use crate::common;

#[test]
fn every_dialect_for_every_material() {
    let opts = common::options();
    for case in common::cases() {
        let prov = common::provenance(&case);
        let input = common::input(&case, &prov, &opts);
        for dialect in Dialect::ALL {
            let files = render(dialect, &input).unwrap_or_else(|e| panic!("{} {}: {e}", dialect.name(), case.key));
            assert!(!files.is_empty(), "{} {}", dialect.name(), case.key);
            let joined: String =
                files.iter().map(|f| format!("===== file: {} =====\n{}", f.name, f.contents)).collect();
            // Filter the version so the snapshot does not change with every release.
            let joined = joined.replace(&format!("cutcal {}", prov.cutcal_version), "cutcal [VERSION]");
            let name = format!("{}_{}", dialect.name(), case.key);
            insta::with_settings!({
                snapshot_path => "snapshots",
                prepend_module_to_snapshot => false,
                omit_expression => true,
            }, {
                insta::assert_snapshot!(name, joined);
            });
        }
    }
}
