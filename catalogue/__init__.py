"""The catalogue: Tables 1 and 2 of Borisov & Mamaev (2002) and the claims of its text, as data.

YAML files (plane.yaml, sphere.yaml, formulas.yaml, references.yaml) validated by
`catalogue.schema`; load them with `catalogue.load.load_catalogue()`.
"""
