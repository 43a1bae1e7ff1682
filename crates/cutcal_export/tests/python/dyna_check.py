"""Checks LS-DYNA keyword decks with PyDyna (ansys-dyna-core), offline (no solver, no server).

usage: python dyna_check.py DECK...
For every deck: PyDyna parses it with no warning and no "Failed to process" summary; every
keyword becomes a keyword class (nothing kept as raw text) of the class its keyword line names
(PyDyna maps unknown variants to the nearest class silently, fe-cards.md section 5.1); every
referenced ID resolves: part -> section, material, EOS, hourglass, thermal material; thermal
material -> heat-capacity and conductivity curves; contact -> parts (SURFxTYP 3), the FS = 2
table and its curves (one per table value, right after the table, in order), LCFST/LCFDT/LCH;
*INITIAL_TEMPERATURE_SET -> a node set or 0 (all nodes). Complete decks (2-D, deck2d.rs) also:
every element -> a part and existing nodes (unique element and node ids); *SET_NODE_LIST ->
nodes; *SET_PART_LIST -> parts; 2-D contact SURFA/SURFB -> part sets (> 0) or node sets (< 0);
*BOUNDARY_SPC_SET -> node sets; *BOUNDARY_PRESCRIBED_MOTION_RIGID -> a part and a curve. Prints "ok <deck> <n> keywords" per
deck; exits 1 with the list of errors otherwise. Used by crates/cutcal_export/tests/it/pydyna.rs.
"""
import re
import sys
import warnings

from ansys.dyna.core import Deck


def camel(keyword_line):
    """'*MAT_JOHNSON_COOK_TITLE' -> 'MatJohnsonCook' (PyDyna class naming; _TITLE/_ID dropped)."""
    name = keyword_line[1:].split()[0].upper()
    for suffix in ("_TITLE", "_ID"):
        if name.endswith(suffix):
            name = name[: -len(suffix)]
    return "".join(p[:1] + p[1:].lower() for p in name.split("_")).replace("2d", "2D")


def ids(value):
    return int(value) if value is not None and value == value else 0


def check(path):
    errors = []
    text = open(path).read()
    deck = Deck()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = deck.loads(text)
    if result.get_summary():
        errors.append(f"summary: {result.get_summary().strip()}")
    errors += [f"warning: {m}" for m in result.warnings] + [f"warning: {w.message}" for w in caught]

    lines = [l for l in text.splitlines() if l.startswith("*")]
    lines = [l for l in lines if l.split()[0].upper() not in ("*KEYWORD", "*END", "*TITLE")]
    kws = list(deck.all_keywords)
    if len(lines) != len(kws):
        errors.append(f"{len(lines)} keyword lines but {len(kws)} keywords parsed")
    for line, kw in zip(lines, kws):
        if isinstance(kw, str):
            errors.append(f"{line}: kept as raw text")
        elif type(kw).__name__.lower() != camel(line).lower():
            errors.append(f"{line}: parsed as {type(kw).__name__}, expected {camel(line)}")

    by = lambda name: [k for k in kws if type(k).__name__ == name]
    sections = {ids(k.secid) for k in by("SectionSolid") + by("SectionShell")}
    mats = {ids(k.mid) for k in kws if type(k).__name__.startswith("Mat") and not type(k).__name__.startswith("MatThermal")}
    thermal = {ids(k.tmid): k for k in kws if type(k).__name__.startswith("MatThermal")}
    eos = {ids(k.eosid) for k in kws if type(k).__name__.startswith("Eos")}
    hourglass = {ids(k.hgid) for k in by("Hourglass")}
    curves = {ids(k.lcid) for k in by("DefineCurve")}
    tables = {ids(k.tbid) for k in by("DefineTable")}
    node_sets = {ids(k.sid) for k in kws if type(k).__name__.startswith("SetNode")}
    parts = set()
    for k in by("Part"):
        for _, row in k.parts.iterrows():
            pid = ids(row["pid"])
            parts.add(pid)
            for field, pool in (("secid", sections), ("mid", mats), ("tmid", set(thermal))):
                if ids(row[field]) not in pool:
                    errors.append(f"part {pid}: {field} {ids(row[field])} not defined")
            for field, pool in (("eosid", eos), ("hgid", hourglass)):
                if ids(row[field]) != 0 and ids(row[field]) not in pool:
                    errors.append(f"part {pid}: {field} {ids(row[field])} not defined")
    if not parts:
        errors.append("no *PART")
    for tmid, k in thermal.items():
        for field in ("hclc", "tclc"):
            if hasattr(k, field) and ids(getattr(k, field)) not in curves:
                errors.append(f"thermal material {tmid}: {field} {ids(getattr(k, field))} not a curve")
    node_ids = set()
    for k in by("Node"):
        col = k.nodes["nid"]
        node_ids.update(int(v) for v in col)
        if len(set(col)) != len(col):
            errors.append("*NODE: duplicate node ids")
    elem_ids = set()
    for k in by("ElementShell"):
        e = k.elements
        if len(set(e["eid"])) != len(e) or elem_ids & set(int(v) for v in e["eid"]):
            errors.append("*ELEMENT_SHELL: duplicate element ids")
        elem_ids.update(int(v) for v in e["eid"])
        for pid in set(int(v) for v in e["pid"]):
            if pid not in parts:
                errors.append(f"*ELEMENT_SHELL: part {pid} not defined")
        for col in ("n1", "n2", "n3", "n4"):
            missing = set(int(v) for v in e[col]) - node_ids
            if missing:
                errors.append(f"*ELEMENT_SHELL: {col} names {len(missing)} undefined nodes, e.g. {sorted(missing)[:3]}")
    for k in kws:
        if type(k).__name__.startswith("SetNodeList"):
            missing = set(int(v) for v in k.nodes if v == v) - node_ids
            if missing or len(k.nodes) == 0:
                errors.append(f"*SET_NODE_LIST {ids(k.sid)}: empty or undefined nodes {sorted(missing)[:3]}")
    part_sets = {}
    for k in by("SetPartList"):
        part_sets[ids(k.sid)] = [int(v) for v in k.parts if v == v]
        if not part_sets[ids(k.sid)] or set(part_sets[ids(k.sid)]) - parts:
            errors.append(f"*SET_PART_LIST {ids(k.sid)}: empty or undefined parts")
    for k in by("BoundarySpcSet"):
        if ids(k.nsid) not in node_sets:
            errors.append(f"*BOUNDARY_SPC_SET: node set {ids(k.nsid)} not defined")
    for k in by("BoundaryPrescribedMotionRigid"):
        if ids(k.pid) not in parts:
            errors.append(f"*BOUNDARY_PRESCRIBED_MOTION_RIGID: part {ids(k.pid)} not defined")
        if ids(k.lcid) not in curves:
            errors.append(f"*BOUNDARY_PRESCRIBED_MOTION_RIGID: curve {ids(k.lcid)} not defined")
    for k in kws:
        if type(k).__name__.startswith("Contact2D"):
            for side in ("a", "b"):
                sid = ids(getattr(k, f"surf{side}"))
                if (sid > 0 and sid not in part_sets) or (sid < 0 and -sid not in node_sets) or sid == 0:
                    errors.append(f"2-D contact: SURF{side.upper()} {sid} is not a part set (> 0) or node set (< 0)")
        elif type(k).__name__.startswith("Contact"):
            for side in ("a", "b"):
                sid, typ = ids(getattr(k, f"surf{side}")), ids(getattr(k, f"surf{side}typ"))
                if typ == 3 and sid not in parts:
                    errors.append(f"contact: SURF{side.upper()} part {sid} not defined")
                elif typ not in (3,):
                    errors.append(f"contact: SURF{side.upper()}TYP {typ} not checked by this script")
            if abs(float(k.fs) - 2.0) < 1e-12 and ids(k.fd) not in tables:
                errors.append(f"contact: FS = 2 but FD {ids(k.fd)} is not a *DEFINE_TABLE")
            for field in ("lcfst", "lcfdt", "lch"):
                if hasattr(k, field) and ids(getattr(k, field)) != 0 and abs(ids(getattr(k, field))) not in curves:
                    errors.append(f"contact: {field} {ids(getattr(k, field))} not a curve")
    for t in by("DefineTable"):
        at = kws.index(t)
        n = len(t.points)
        follow = kws[at + 1 : at + 1 + n]
        if n == 0 or len(follow) != n or not all(type(c).__name__ == "DefineCurve" for c in follow):
            errors.append(f"table {ids(t.tbid)}: its {n} values are not followed by {n} curves")
    for k in by("InitialTemperatureSet"):
        for _, row in k.sets.iterrows():
            nsid = ids(row["nsid"])
            if nsid != 0 and nsid not in node_sets:
                errors.append(f"*INITIAL_TEMPERATURE_SET: node set {nsid} not defined")
    return errors, len(kws)


def main(paths):
    failed = False
    for path in paths:
        errors, n = check(path)
        if errors:
            failed = True
            for e in errors:
                print(f"ERROR {path}: {e}")
        else:
            print(f"ok {path} {n} keywords")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
