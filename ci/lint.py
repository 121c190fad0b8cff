#!/usr/bin/env python3
"""Checks the hosted CI's pipelines (ci/*.yml, GitHub Actions workflows)
against the workflow schema in ci/schema/ (SchemaStore's, as vendored by
check-jsonschema): they cannot run here, so a typo would otherwise wait for
the first hosted run. Prints one line per file; exit 1 on any error."""
import json
import pathlib
import sys

import jsonschema
import yaml

here = pathlib.Path(__file__).resolve().parent
schema = json.loads((here / "schema" / "github-workflows.json").read_text())
validator = jsonschema.Draft7Validator(schema)
files = sorted(here.glob("*.yml"))
if not files:
    sys.exit("ci/lint.py: no pipelines in ci/")
failed = 0
for path in files:
    # YAML 1.1 reads a bare `on:` key as True; GitHub reads it as "on".
    doc = yaml.safe_load(path.read_text())
    if isinstance(doc, dict) and True in doc:
        doc["on"] = doc.pop(True)
    errors = sorted(validator.iter_errors(doc), key=lambda e: list(e.absolute_path))
    for e in errors:
        where = "/".join(str(p) for p in e.absolute_path) or "(top)"
        print(f"ci/{path.name}: {where}: {e.message[:300]}", file=sys.stderr)
    failed += bool(errors)
    if not errors:
        print(f"ci/lint: ci/{path.name} is a valid workflow", file=sys.stderr)
sys.exit(1 if failed else 0)
