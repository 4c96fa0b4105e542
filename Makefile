# lozenge — one entry point for everything. `make help` lists the targets; lib/README.md
# describes the layout.
#
# The library liblz.a is the core (lib/core/*.c), each stage's library half
# (lib/NN-name/*.c) and, for every stage, the graded files of the chosen
# implementation: IMPL=solutions|assignments sets all stages, IMPL_NN=... one stage.
# Objects of the two implementations live apart, and build/impl.stamp records the
# current choice, so switching IMPL relinks exactly what changed. The `lz` program
# (lib/app/) is linked on top of it, into build/bin/lz and the library's own test
# suite; the student tests and the lesson drivers link the library alone.

SHELL := /bin/bash
.DEFAULT_GOAL := all
.SUFFIXES:
MAKEFLAGS += --no-builtin-rules
.DELETE_ON_ERROR:
.SECONDARY:

SANITIZE ?= 0
ifeq ($(SANITIZE),1)
BUILD ?= build/sanitize
else
BUILD ?= build
endif

# ---- stages and the implementation choice --------------------------------
STAGES := $(sort $(notdir $(wildcard assignments/[0-9][0-9]-*)))
nn = $(firstword $(subst -, ,$(1)))
stage_named = $(firstword $(filter $(1)-%,$(STAGES)) $(filter $(1),$(STAGES)))

ifneq ($(wildcard solutions/.),)
IMPL ?= solutions
else
IMPL ?= assignments
endif
$(foreach s,$(STAGES),$(eval IMPL_$(call nn,$(s)) ?= $(IMPL)))
$(foreach s,$(STAGES),$(if $(filter solutions assignments,$(IMPL_$(call nn,$(s)))),,\
  $(error IMPL_$(call nn,$(s)) = '$(IMPL_$(call nn,$(s)))': allowed values are solutions and assignments)))
$(foreach s,$(STAGES),$(if $(filter solutions,$(IMPL_$(call nn,$(s)))),$(if $(wildcard solutions/$(s)/.),,\
  $(error IMPL_$(call nn,$(s))=solutions but solutions/$(s) is not here (a student tree has only assignments/)))))
impl_of = $(IMPL_$(call nn,$(1)))

# ---- flags ---------------------------------------------------------------
# pkg-config is asked when a recipe runs (deferred '='), so `make check` can
# install the packages first and then build with their flags.
PKG_CFLAGS = $(shell pkg-config --cflags gsl check 2>/dev/null)
GSL_LIBS = $(shell pkg-config --libs gsl 2>/dev/null || echo -lgsl -lgslcblas)
CHECK_LIBS = $(shell pkg-config --libs check 2>/dev/null || echo -lcheck)
WARN := -Wall -Wextra -Werror -Wno-unused-parameter -Wshadow -Wstrict-prototypes \
        -Wmissing-prototypes -Wvla
OPT ?= -O2
CFLAGS ?= $(OPT) -g
CFLAGS += -std=c11 -D_XOPEN_SOURCE=700 $(WARN) -Ilib/include
LDLIBS := -lm -pthread  # -pthread: lz takes SIGINT and SIGTERM in a thread of its own
ifeq ($(SANITIZE),1)
CFLAGS += -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer
LDFLAGS += -fsanitize=address,undefined
endif

# Stamps change only when their content does: they make a flag or IMPL switch rebuild.
CONFIG := $(foreach s,$(STAGES),$(call nn,$(s))=$(call impl_of,$(s)))
FLAGS_SIG := $(CC) $(CFLAGS) $(LDFLAGS)
$(shell mkdir -p $(BUILD) && { [ "$$(cat $(BUILD)/impl.stamp 2>/dev/null)" = "$(CONFIG)" ] || echo "$(CONFIG)" > $(BUILD)/impl.stamp; })
$(shell { [ "$$(cat $(BUILD)/flags.stamp 2>/dev/null)" = '$(FLAGS_SIG)' ] || echo '$(FLAGS_SIG)' > $(BUILD)/flags.stamp; })

# ---- the library ---------------------------------------------------------
LIB_OBJS := $(patsubst lib/%.c,$(BUILD)/obj/lib/%.o,$(wildcard lib/core/*.c lib/[0-9][0-9]-*/*.c))
stage_objs = $(patsubst $(call impl_of,$(1))/$(1)/%.c,$(BUILD)/obj/$(call impl_of,$(1))/$(1)-%.o,\
             $(wildcard $(call impl_of,$(1))/$(1)/*.c))
STAGE_OBJS := $(foreach s,$(STAGES),$(call stage_objs,$(s)))
LIB := $(BUILD)/lib/liblz.a

COMPILE = @mkdir -p $(@D); echo "  CC      $<"; $(CC) $(CFLAGS) $(PKG_CFLAGS) $(EXTRA_INC) -MMD -MP -c $< -o $@
LINK = @mkdir -p $(@D); echo "  LD      $@"; $(CC) $(LDFLAGS) -o $@ $(filter %.o %.a,$^) $(EXTRA_LIBS) $(GSL_LIBS) $(LDLIBS)

$(BUILD)/obj/lib/%.o: lib/%.c $(BUILD)/flags.stamp
	$(COMPILE)
# The literature tables are read from this tree's datasets/reference ($LZ_REFERENCE_DIR overrides).
$(BUILD)/obj/lib/core/reference.o: EXTRA_INC = -DLZ_REFERENCE_DIR='"$(abspath datasets/reference)"'
# Stage objects are named <stage>-<file>.o so that archive members never collide.
define stage_rule
$(BUILD)/obj/$(2)/$(1)-%.o: $(2)/$(1)/%.c $(BUILD)/flags.stamp
	$$(COMPILE)
endef
$(foreach s,$(STAGES),$(foreach i,solutions assignments,$(eval $(call stage_rule,$(s),$(i)))))

$(LIB): $(LIB_OBJS) $(STAGE_OBJS) $(BUILD)/impl.stamp
	@mkdir -p $(@D); rm -f $@; echo "  AR      $@"; ar rcs $@ $(filter %.o,$^)

# ---- the lz program: CLI, scene parser, the engines' scene bindings -------
LZ := $(BUILD)/bin/lz
APP_OBJS := $(patsubst lib/app/%.c,$(BUILD)/obj/app/%.o,$(filter-out lib/app/lz.c,$(wildcard lib/app/*.c)))
$(BUILD)/obj/app/%.o: lib/app/%.c $(BUILD)/flags.stamp
	$(COMPILE)
# `lz list` finds the scenes of this tree from anywhere ($LZ_SCENES overrides).
$(BUILD)/obj/app/cli.o: EXTRA_INC = -DLZ_SCENE_DIR='"$(abspath datasets/scenes)"'
$(LZ): $(BUILD)/obj/app/lz.o $(APP_OBJS) $(LIB)
	$(LINK)

# ---- lz-mpi: the pedmd scenes with one process per rank, where mpicc is ----
# The MPI back-end (lib/06-parallel/mpi/) is outside the library's wildcard: liblz.a
# needs no MPI. Only these objects and the link use mpicc (private: not the library's).
MPICC ?= mpicc
HAVE_MPI := $(shell command -v $(MPICC) >/dev/null 2>&1 && echo 1)
LZ_MPI := $(BUILD)/bin/lz-mpi
MPI_OBJS := $(BUILD)/obj/mpi/msg_mpi.o $(BUILD)/obj/mpi/lz_mpi.o
$(BUILD)/obj/mpi/msg_mpi.o: lib/06-parallel/mpi/msg_mpi.c $(BUILD)/flags.stamp
	$(COMPILE)
$(BUILD)/obj/mpi/lz_mpi.o: lib/app/mpi/lz_mpi.c $(BUILD)/flags.stamp
	$(COMPILE)
$(BUILD)/obj/mpi/lz_mpi.o: EXTRA_INC = -Ilib/app
$(MPI_OBJS) $(LZ_MPI): private CC = $(MPICC)
$(LZ_MPI): $(MPI_OBJS) $(APP_OBJS) $(LIB)
	$(LINK)

# ---- tests ---------------------------------------------------------------
RUNNER_OBJ := $(BUILD)/obj/grade/runner.o
$(BUILD)/obj/grade/%.o: tests/grade/%.c $(BUILD)/flags.stamp
	$(COMPILE)
$(BUILD)/obj/tests/%.o: EXTRA_INC = -Itests/grade
$(BUILD)/obj/tests/lib/%.o: EXTRA_INC = -Itests/grade -Ilib/app
$(BUILD)/obj/tests/%.o: tests/%.c $(BUILD)/flags.stamp
	$(COMPILE)
test_objs = $(patsubst tests/%.c,$(BUILD)/obj/tests/%.o,$(wildcard tests/$(1)/*.c tests/$(1)/hidden/*.c))
# The library's own suite also tests the lz program; the stage suites link the library alone.
define test_rule
$(BUILD)/tests/$(1): $(call test_objs,$(1)) $(RUNNER_OBJ) $(if $(filter lib,$(1)),$(APP_OBJS)) $(LIB)
	$$(LINK)
endef
TEST_SUITES := lib $(STAGES)
$(foreach t,$(TEST_SUITES),$(eval $(call test_rule,$(t))))
$(TEST_SUITES:%=$(BUILD)/tests/%): EXTRA_LIBS = $(CHECK_LIBS)
# A stage's rubrics in the order the lesson assigns the work (lib/tools/common.sh says how).
rubrics = $(shell bash -c '. lib/tools/common.sh && rubrics_of "$$1"' rubrics $(1))
TEST_BINS := $(TEST_SUITES:%=$(BUILD)/tests/%)

# The report writer of the autograder links no student code.
REPORT := $(BUILD)/bin/lz-report
$(REPORT): $(BUILD)/obj/grade/report.o
	$(LINK)

# ---- lesson drivers: lessons/NN-name/X.c -> build/lessons/NN/bin/X ----
define lesson_rule
$(BUILD)/obj/lessons/$(1)/%.o: lessons/$(1)/%.c $(BUILD)/flags.stamp
	$$(COMPILE)
$(BUILD)/lessons/$(call nn,$(1))/bin/%: $(BUILD)/obj/lessons/$(1)/%.o $(LIB)
	$$(LINK)
endef
$(foreach s,$(STAGES),$(eval $(call lesson_rule,$(s))))
DRIVERS := $(foreach s,$(STAGES),$(patsubst lessons/$(s)/%.c,$(BUILD)/lessons/$(call nn,$(s))/bin/%,$(wildcard lessons/$(s)/*.c)))

-include $(shell find $(BUILD)/obj -name '*.d' 2>/dev/null)

# ---- user targets --------------------------------------------------------
.PHONY: all tests check check-run test grade grade-all lesson demo slides bench \
        assignments handout submit mutants deps clean help need-stage mpi-check
all: $(LIB) $(LZ) $(DRIVERS) $(if $(HAVE_MPI),$(LZ_MPI))
tests: $(TEST_BINS) $(REPORT) $(LZ)

deps:
	@bash lib/tools/deps.sh

# `make check` is the test command (CI runs it): it installs what is missing first.
check: deps
	@$(MAKE) --no-print-directory check-run

check-run: all tests
	@bash lib/tools/check.sh "$(BUILD)" "$(STAGES)"

need-stage:
	@if [ -z "$(STAGE)" ] || [ -z "$(call stage_named,$(STAGE))" ]; then \
	  echo "make: say which stage, e.g. STAGE=01; the stages here are: $(STAGES)" >&2; exit 2; fi

# One stage's tests, student view: a line per test, the failure in physics words.
test: need-stage
	@$(MAKE) --no-print-directory $(BUILD)/tests/$(call stage_named,$(STAGE))
	@$(BUILD)/tests/$(call stage_named,$(STAGE)) $(foreach r,$(call rubrics,$(call stage_named,$(STAGE))),--rubric $(r))

grade:
	@bash tests/grade/grade.sh --build "$(BUILD)" --submission "$(SUBMISSION)" \
	  --stage "$(STAGE)" --isolate "$(ISOLATE)" $(if $(OUT),--out "$(OUT)")

grade-all:
	@if [ -z "$(SUBS)" ]; then echo "make grade-all: SUBS=dir (one sub-directory or .tar.gz per student)" >&2; exit 2; fi
	@bash tests/grade/grade.sh --build "$(BUILD)" --all "$(SUBS)" --stage "$(STAGE)" --isolate "$(ISOLATE)" $(if $(OUT),--out "$(OUT)")

# A lesson's experiments: drivers, then plots, then the stage's scenes (QUICK=1: demo size).
lesson: need-stage all
	@bash lib/tools/lesson.sh "$(call stage_named,$(STAGE))" "$(BUILD)" "$(QUICK)"

demo: deps
	@$(MAKE) --no-print-directory all
	@for s in $(STAGES); do bash lib/tools/lesson.sh "$$s" "$(BUILD)" 1 || exit 1; done
	@bash lib/tools/demo.sh "$(BUILD)" "$(STAGES)"

slides: all
	@bash lib/tools/slides.sh "$(BUILD)" "$(STAGES)"

bench: all
	@bash lib/tools/bench.sh "$(BUILD)"
	@bash lib/tools/bench-mpi.sh "$(BUILD)"

assignments:
	@bash lib/tools/mkassign.sh solutions assignments

# Realistic student bugs (tests/NN-name/mutants/*.patch) against the graded tests.
mutants: all tests
	@bash tests/grade/mutants.sh "$(BUILD)" $(if $(STAGE),$(call stage_named,$(STAGE)))

handout:
	@bash lib/tools/handout.sh "$(BUILD)"

# lz-mpi on P = 1 .. 4 processes against the serial run (skipped without MPI).
mpi-check: $(if $(HAVE_MPI),$(LZ_MPI))
	@bash tests/mpi/check.sh "$(BUILD)"

# The student's submission: exactly the files the MANIFESTs name, listed.
submit:
	@bash lib/tools/submit.sh "$(BUILD)"

clean:
	rm -rf build

help:
	@echo "make deps | all | check | test STAGE=NN | grade [SUBMISSION=dir|x.tar.gz] [STAGE=NN] [ISOLATE=1]"
	@echo "make grade-all SUBS=dir | submit | lesson STAGE=NN [QUICK=1] | demo | slides | bench | assignments | handout | mutants [STAGE=NN] | mpi-check | clean"
	@echo "$(if $(wildcard solutions/.),IMPL=solutions|assignments (now: $(CONFIG)); IMPL_NN=... for one stage,your code in assignments/ (now: $(CONFIG))); SANITIZE=1 for ASan+UBSan"
