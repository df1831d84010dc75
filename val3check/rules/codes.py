"""Every rule code, one constant each, named after its rule (`rules/CODE.toml` `name`), with the
module that emits it: from a code a reader goes to its doc (`rules/CODE.toml`, `val3check rule CODE`),
its implementation (the module named here) and its tests (the examples of the TOML file, run by
`tests/test_rule_examples.py`). `tests/test_rule_codes.py` holds this map to the rule files and to the code."""

from __future__ import annotations

# syntax and files (F)
FILE_NOT_FOUND = "F001"                   # confine.py, loading/loader.py
FILE_TOO_LARGE = "F002"                   # confine.py
INVALID_UTF8 = "F003"                     # loading/xmlread.py
MALFORMED_XML = "F004"                    # loading/xmlread.py
FORBIDDEN_ENTITY = "F005"                 # loading/xmlread.py
UNEXPECTED_DOCUMENT = "F006"              # loading/document_kind.py
INVALID_DECLARATION = "F007"              # loading/declaration.py
NO_APPLICATION_FOUND = "F008"             # loading/loader.py
NO_PROJECT_FILE = "F009"                  # loading/loader.py
PROGRAM_WITHOUT_CODE = "F010"             # loading/program_file.py
DUPLICATE_FILE_DECLARATION = "F011"       # loading/data_file.py, loading/loader.py
PROGRAM_FILE_NOT_LISTED = "F012"          # loading/loader.py
LISTED_FILE_OUTSIDE_APPLICATION = "F013"  # loading/loader.py
PATH_OUTSIDE_ROOTS = "F014"               # confine.py, loading/libraries.py, loading/loader.py
CODE_ELEMENT_IGNORED = "F015"             # loading/program_file.py
LIBRARY_FOUND_IN_REPOSITORY = "F016"      # loading/libraries.py
NUMBER_OUT_OF_RANGE = "F017"              # semantics/limits.py
SYNTAX_ERROR = "F101"                     # parsing/engine.py, parsing/parser.py
INVALID_CHARACTER = "F102"                # parsing/engine.py
INVALID_NUMBER = "F103"                   # parsing/engine.py
TOO_DEEPLY_NESTED = "F104"                # parsing/parser.py

# names and declarations (N)
UNDEFINED_VARIABLE = "N001"               # semantics/expressions.py
UNDEFINED_PROGRAM = "N002"                # semantics/statements.py
UNDEFINED_INSTRUCTION = "N003"            # semantics/calls.py
UNKNOWN_INSTRUCTION = "N004"              # semantics/calls.py
UNDEFINED_LIBRARY_ALIAS = "N005"          # semantics/expressions.py
NAME_CASE_MISMATCH = "N006"               # semantics/expressions.py, semantics/statements.py
DUPLICATE_LOCAL = "N007"                  # semantics/declarations.py
INVALID_NAME = "N008"                     # semantics/declarations.py
START_STOP_WITH_PARAMETERS = "N009"       # semantics/declarations.py
UNDEFINED_TYPE = "N010"                   # semantics/declarations.py
WRONG_ARM_FAMILY = "N011"                 # semantics/declarations.py
NAME_TOO_LONG = "N012"                    # semantics/declarations.py
NAME_STARTS_WITH_UNDERSCORE = "N013"      # semantics/declarations.py
FATHER_NOT_FOUND = "N014"                 # semantics/limits.py
MIXED_ARM_FAMILIES_UNKNOWN_ARM = "N016"   # semantics/declarations.py

# types and containers (T)
OPERATOR_NOT_DEFINED = "T001"             # semantics/expressions.py
CONDITION_NOT_BOOL = "T002"               # semantics/statements.py
ASSIGNMENT_TYPE_MISMATCH = "T003"         # semantics/expressions.py
ASSIGNMENT_IN_EXPRESSION = "T004"         # semantics/expressions.py
WRONG_ARGUMENT_COUNT = "T005"             # semantics/calls.py
ARGUMENT_TYPE_MISMATCH = "T006"           # semantics/calls.py, semantics/statements.py
REFERENCE_NEEDS_VARIABLE = "T007"         # semantics/calls.py, semantics/statements.py
CONTAINER_MISMATCH = "T008"               # semantics/calls.py
WRONG_INDEX_COUNT = "T009"                # semantics/expressions.py
WRONG_INDEX_TYPE = "T010"                 # semantics/expressions.py
MISSING_INDEX = "T011"                    # semantics/calls.py, semantics/expressions.py
UNKNOWN_FIELD = "T012"                    # semantics/expressions.py
NOT_ASSIGNABLE = "T013"                   # semantics/expressions.py
CASE_TYPE_MISMATCH = "T014"               # semantics/statements.py
BAD_FOR_HEADER = "T015"                   # semantics/statements.py
DIO_ASSIGNMENT_REMOVED = "T016"           # semantics/expressions.py
BAD_STRUCTURED_LITERAL = "T017"           # semantics/expressions.py
PROGRAM_INSTRUCTION_MISUSE = "T018"       # semantics/calls.py, semantics/expressions.py, semantics/statements.py
NO_RETURN_VALUE = "T019"                  # semantics/calls.py
UNEXPECTED_INDEX = "T020"                 # semantics/calls.py
ARRAY_RESIZE_NOT_ALLOWED = "T021"         # semantics/calls.py
TASK_REFERENCE_TO_LOCAL = "T022"          # semantics/calls.py, semantics/statements.py
INVALID_TASK_CONSTANT = "T023"            # semantics/statements.py
S8_SIGNATURE_UNVERIFIED = "T024"          # semantics/calls.py
BARE_MULTI_VALUE_ARRAY = "T025"           # semantics/expressions.py
ARRAY_DIMENSION_OVER_LIMIT = "T026"       # semantics/limits.py
ARRAY_VALUES_OVER_LIMIT = "T027"          # semantics/limits.py
S8_ONLY = "T030"                          # semantics/context.py
S8_ON_S7_TARGET = "T031"                  # semantics/context.py

# libraries and user types (L)
LIBRARY_NOT_FOUND = "L001"                # loading/libraries.py
USER_TYPE_NOT_FOUND = "L002"              # loading/libraries.py
IO_LIBRARY_NOT_CHECKED = "L003"           # loading/libraries.py
CIRCULAR_LIBRARY = "L004"                 # loading/libraries.py
CIRCULAR_USER_TYPE = "L005"               # loading/libraries.py
UNDEFINED_LIBRARY_SYMBOL = "L010"         # semantics/calls.py, semantics/expressions.py, semantics/statements.py
PRIVATE_LIBRARY_SYMBOL = "L011"           # semantics/expressions.py, semantics/statements.py
LIBRARY_SYMBOL_KIND = "L012"              # semantics/calls.py, semantics/expressions.py, semantics/statements.py
UNDEFINED_USER_TYPE_FIELD = "L013"        # semantics/expressions.py

# suspicious patterns (S)
UNUSED_LOCAL = "S001"                     # semantics/patterns_messages.py
UNUSED_PARAMETER = "S002"                 # semantics/patterns_messages.py
UNUSED_GLOBAL = "S003"                    # semantics/patterns_messages.py
UNUSED_PRIVATE_PROGRAM = "S004"           # semantics/patterns_messages.py
READ_BEFORE_ASSIGNMENT = "S005"           # semantics/patterns_messages.py
UNREACHABLE_CODE = "S006"                 # semantics/patterns_messages.py
MOVE_ID_EQUALITY = "S007"                 # semantics/patterns_messages.py
NUM_EQUALITY = "S008"                     # semantics/patterns_messages.py
CASE_WITHOUT_BREAK = "S009"               # semantics/patterns_messages.py
COMMENT_AFTER_CODE = "S010"               # semantics/patterns_messages.py
STRING_TOO_LONG = "S011"                  # semantics/patterns_messages.py
WAIT_NEVER_CHANGES = "S012"               # semantics/patterns_messages.py
NESTED_FOR_SAME_COUNTER = "S013"          # semantics/patterns_messages.py
BUSY_WAIT_LOOP = "S014"                   # semantics/patterns_messages.py
SELF_ASSIGNMENT = "S015"                  # semantics/patterns_messages.py
UNKNOWN_SUPPRESSION_CODE = "S020"         # suppression.py
UNUSED_SUPPRESSION = "S021"               # suppression.py

# runtime and simulation (R)
RUNTIME_ERROR = "R001"                    # interpretation/machine.py
ARM_NOT_SIMULATED = "R002"                # interpretation/not_simulated.py
DEADLOCK = "R003"                         # interpretation/deadlock.py, simulation/moving_arm.py
NOT_SIMULATED = "R004"                    # interpretation/not_simulated.py
SYNC_OVERRUN = "R005"                     # interpretation/machine.py
BUDGET_EXCEEDED = "R006"                  # interpretation/machine.py, simulation/collect.py, simulation/folding.py
DURATION_REACHED = "R007"                 # simulation/collect.py
SCENARIO_REACTION_LOOP = "R008"           # interpretation/io_cell.py
INPUT_NEVER_DRIVEN = "R009"               # interpretation/deadlock.py
TARGET_OUT_OF_REACH = "R010"              # motion/findings.py
JOINT_LIMIT = "R011"                      # motion/findings.py
CONFIGURATION_CHANGE = "R012"             # motion/findings.py
PATH_THROUGH_SINGULARITY = "R013"         # motion/findings.py
NEAR_SINGULARITY = "R014"                 # motion/findings.py
CIRCLE_UNDEFINED = "R015"                 # motion/findings.py
MOVEJ_NO_OP = "R016"                      # motion/findings.py
INVALID_MDESC = "R017"                    # motion/findings.py
MOTION_WITHOUT_POWER = "R018"             # interpretation/machine.py, motion/findings.py, simulation/moving_arm.py
SLOW_SAFE_PROFILE = "R019"                # motion/findings.py
CELL_FILE_INVALID = "R030"                # simulation/collision_run.py
COLLISION_WITH_CELL = "R031"              # simulation/collision_run.py
MOTION_STARTS_IN_COLLISION = "R032"       # simulation/collision_run.py
NEAR_MISS = "R033"                        # simulation/collision_run.py
SELF_COLLISION = "R034"                   # simulation/collision_run.py
PART_LEFT_IN_COLLISION = "R035"           # simulation/collision_run.py
CELL_FRAME_WITHOUT_VALUE = "R036"         # simulation/collision_run.py
COLLISIONS_NOT_CHECKED = "R037"           # simulation/collision_run.py, simulation/run.py
LIBRARY_NOT_LOADED = "R040"               # interpretation/machine.py
OUTSIDE_THE_SIMULATION = "R041"           # interpretation/machine.py
OPTION_LICENCE_ASSUMED = "R050"           # simulation/ch11_licences.py
LATCH_NOT_FAST_INPUT = "R051"             # simulation/ch09_latch.py
OPTION_EFFECT_NOT_SIMULATED = "R052"      # simulation/alteration.py, simulation/ch11_absolute.py, simulation/ch11_compliance.py, simulation/ch11_continuous.py
COMPLIANT_MOVE_LIMITATION = "R053"        # simulation/ch11_compliance.py
COMPLIANT_MOVE_ON_SURFACE = "R054"        # simulation/compliance.py
ALTERATION_INVALID = "R055"               # simulation/alteration.py
