# A family of studies (config/families/<family>.yaml) in one run: every variant of the
# family's grid is this workflow's Snakefile instantiated as a Snakemake module with the
# variant's config (results under results/studies/<family>/<variant>/, rules renamed
# <variant>__<rule>); the shared demo inputs have one rule each; rule `all` asks for every
# variant's results and the family's comparison page. contactlab.studies.family expands the
# grid and adapts what Snakemake keys by rule name (profile resources, groups, localrules).

import os


from contactlab.config_check import ConfigError, check_config, load_yaml_file, parse_yaml, refuse
from contactlab.studies.family import (
    SHARED_RULES,
    FamilyError,
    rename_localrules,
    split_family,
    use_variant,
    variant_config,
)
from contactlab.rulehelpers import demo_image_folders
from contactlab.schema import SCHEMA_PATH
from contactlab.studies import cluster, manifest, names, reads, reuse, shared
from contactlab.studies.jobkeys import StudyFolders
from contactlab.provenance import STUDIES_ENV, PROVENANCE_ENV, coerce

_FAMILY_FILE = next((str(f) for f in workflow.config_settings.configfiles
                     if "family" in load_yaml_file(f)), "--config")
try:
    FAMILY, VARIANTS, _FAMILY_BASE = split_family(config, _FAMILY_FILE)
except FamilyError as exc:
    refuse(f"invalid family: {exc}")
_CLASH = names.clash(FAMILY, _FAMILY_FILE)
if _CLASH:
    refuse(f"invalid family: {_CLASH}")

FAMILY_GRID = config["grid"]

# every variant checked before any is read, each problem blamed on the family file
_SCHEMA = parse_yaml(SCHEMA_PATH.read_text(encoding="utf-8"))
_SOURCES = [(str(f), load_yaml_file(f)) for f in map(str, workflow.configfiles)]
for _variant in VARIANTS:
    _config = coerce(variant_config(_FAMILY_BASE, _variant), _SCHEMA)
    try:
        check_config(_config, _SCHEMA, [
            *_SOURCES, (f"{_FAMILY_FILE} (variant {_variant.name})", _variant.overrides())])
    except ConfigError as exc:
        refuse(str(exc))

# the variants' jobs find their own study's provenance in this table (contactlab.provenance)
for _var in (STUDIES_ENV, *PROVENANCE_ENV.values()):
    os.environ.pop(_var, None)
for _i, _variant in enumerate(VARIANTS):
    use_variant(workflow, _variant, variant_config(_FAMILY_BASE, _variant),
                os.path.join(workflow.basedir, "Snakefile"), shared_rules=_i == 0)
rename_localrules(workflow, VARIANTS)

#: each variant's module namespace (its RESULTS, STUDY_TARGETS, PROVENANCE)
_MODULES = {v.name: globals()[v.prefix] for v in VARIANTS}
FAMILY_TARGETS = [f for m in _MODULES.values() for f in m.STUDY_TARGETS]


shared.attach(workflow, SHARED_RULES, reads.data(_MODULES[VARIANTS[0].name].config),
              demo_image_folders(_MODULES[VARIANTS[0].name].TESTS))
cluster.install(workflow)  # why a Slurm job failed, in the run's own output
# the variants' jobs with the same key run once; those another study ran are linked
reuse.install(workflow, [StudyFolders(v.study, m.RESULTS, m.LOGS)
                         for v, m in zip(VARIANTS, _MODULES.values(), strict=True)],
              shared.SHARED_FOLDERS)
RUN_STUDIES = [{"logs": m.LOGS, "targets": m.STUDY_TARGETS, "recorder": m.READS,
                "all_rules": ["all", f"{v.prefix}__all"], **m.PROVENANCE}
               for v, m in zip(VARIANTS, _MODULES.values(), strict=True)]


include: "compare.smk"


onsuccess:
    manifest.record_runs(workflow, RUN_STUDIES, manifest.run_config_files(workflow), success=True)


onerror:
    manifest.record_runs(workflow, RUN_STUDIES, manifest.run_config_files(workflow), success=False)


localrules:
    all,


rule all:
    """Every result of every variant of the family, and the family's comparison page."""
    default_target: True
    input:
        FAMILY_TARGETS,
        FAMILY_COMPARE_PAGE,
