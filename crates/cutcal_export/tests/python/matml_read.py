"""Reads MatML files with ansys-materials-manager's MatmlReader, unchanged, and prints what it read.

usage: python matml_read.py FILE...
Prints one JSON object {file: {material: {property: {parameter: [values]}}}} on stdout. Exits 1
if a file cannot be read or a property or parameter comes back without values. Used by
crates/cutcal_export/tests/it/ansys_matml.rs, which compares the values with the material data.
"""
import contextlib
import json
import sys
import warnings

from ansys.materials.manager.parsers.matml.matml_reader import MatmlReader


def as_list(data):
    if isinstance(data, (list, tuple)):
        return [float(x) for x in data]
    return [float(data)]


def main(paths):
    out = {}
    for path in paths:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", DeprecationWarning)
            reader = MatmlReader(path)
            materials = reader.materials
        file_out = {}
        for name, props in materials.items():
            mat_out = {}
            for prop_name, prop in props.items():
                params = {p_name: as_list(p.data) for p_name, p in prop.parameters.items()}
                if not params:
                    print(f"{path}: {name}: property {prop_name!r} has no parameter values", file=sys.stderr)
                    return 1
                mat_out[prop_name] = params
            file_out[name] = mat_out
        out[path] = file_out
        # The reader's conversion into its material models must accept the file too (it prints
        # the properties it has no model for, e.g. Johnson Cook Strength: kept off stdout).
        with contextlib.redirect_stdout(sys.stderr):
            reader.convert_matml_materials()
    print(json.dumps(out))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
