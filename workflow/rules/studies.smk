# Studies side by side: the study's final targets, the record each run leaves in the study's
# log folder (study.json: targets, what each was made with; read by `contactlab studies list`),
# and the inputs all studies share, built once under a lock before a run plans them
# (contactlab.studies.manifest, contactlab.studies.shared). In a family run
# (workflow/rules/family.smk) this file is read once per variant; the handlers and the
# shared-input hook are then the family's.

import os

from contactlab.rulehelpers import demo_image_folders
from contactlab.studies import cluster, manifest, reads, reuse, shared
from contactlab.studies.family import SHARED_RULES
from contactlab.studies.jobkeys import StudyFolders

#: every final result of the study and its report page (the inputs of rule `all`)
STUDY_TARGETS = [*ALL_TARGETS, result("report/index.html")]
#: the run's --configfile list (recorded in study.json)
CONFIG_FILES = manifest.run_config_files(workflow)


# (the run that builds the shared inputs for another leaves no record: it is not a study's)
if workflow.modifier.is_main_snakefile() and not os.environ.get(shared.BUILDING_ENV):
    RUN_STUDIES = [{"logs": LOGS, "targets": STUDY_TARGETS, "all_rules": ["all"],
                    "recorder": READS, **PROVENANCE}]
    shared.attach(workflow, SHARED_RULES, reads.data(config), demo_image_folders(TESTS))
    # jobs whose key another study has run are linked, not run (contactlab.studies.reuse)
    reuse.install(workflow, [StudyFolders(PROVENANCE["study"], RESULTS, LOGS)],
                  shared.SHARED_FOLDERS)
    cluster.install(workflow)  # why a Slurm job failed, in the run's own output

    onsuccess:
        manifest.record_runs(workflow, RUN_STUDIES, CONFIG_FILES, success=True)

    onerror:
        manifest.record_runs(workflow, RUN_STUDIES, CONFIG_FILES, success=False)
