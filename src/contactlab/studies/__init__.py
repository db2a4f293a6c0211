"""Studies side by side: list them, compare them, run families of them.

- :mod:`contactlab.studies.effective`: a study's effective config and its hash, from files
  only, as a run computes them (the Snakefile's start-up).
- :mod:`contactlab.studies.manifest`: the record a run leaves in its study's folder
  (``study.json``): the study's targets and what each was made with.
- :mod:`contactlab.studies.catalog`: every study, what it changes, whether it is complete
  and whether it is stale (``contactlab studies list``).
- :mod:`contactlab.studies.headline`: the headline results of each branch, read from a
  study's result files.
- :mod:`contactlab.studies.diff`: parameters and headline results of several studies side by
  side (``contactlab studies diff``).
- :mod:`contactlab.studies.compare`: a comparison page of several studies
  (``config/compare/<name>.yaml``).
- :mod:`contactlab.studies.family`: a grid of overrides as named studies
  ``<family>/<variant>`` run in one Snakemake invocation (``config/families/<name>.yaml``).
- :mod:`contactlab.studies.shared`: the inputs every study shares, built once under a lock.
- :mod:`contactlab.studies.cluster`: why a cluster job failed, from Slurm's records.

The modules the Snakefile loads at start-up (effective, manifest, family, shared) import
only the standard library (and PyYAML/jsonschema, which Snakemake loads anyway).
"""
