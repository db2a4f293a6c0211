# Start-up: validate the config and the test sheet, define the shared target lists.
# Every branch's rule file appends its final outputs to ALL_TARGETS and its report
# fragment to REPORT_SECTIONS; `rule all` and the report index take them from here.

from pathlib import Path

from snakemake.exceptions import WorkflowError
from snakemake.utils import validate

from contactlab.stiffness.demo import demo_data_files
from contactlab.testsheet import TestSheetError, check_data_files, read_test_sheet


def _config_files():
    files = [str(f) for f in workflow.configfiles]
    return ", ".join(files) if files else "the --config values"


try:
    validate(config, "../schemas/config.schema.yaml")
except WorkflowError as exc:
    raise WorkflowError(f"invalid configuration in {_config_files()}:\n{exc}") from None

try:
    TESTS = read_test_sheet(config["tests"])
    validate(TESTS, "../schemas/tests.schema.yaml")
    check_data_files(TESTS, config["tests"], generated=demo_data_files())
except TestSheetError as exc:
    raise WorkflowError(str(exc)) from None
except WorkflowError as exc:
    raise WorkflowError(f"invalid test sheet {config['tests']}:\n{exc}") from None

TEST_IDS = list(TESTS["id"])
PUBLISHED = Path(config["published_dir"])

ALL_TARGETS = []
REPORT_SECTIONS = []
