# rockdem — build, run, test. `make run` and `make test` install missing Debian packages first.
CC      ?= cc
PKGS    := hdf5-serial gsl
# Optimisation, chosen by measurement (gcc 12, least of 3 interleaved runs on 2 shared cores,
# ns per active subcontact-step, -O2 -> -O3, x86-64-v2): corner block 89 -> 78, bed 128 -> 110,
# PBR 55 -> 45, 20-drum column 145 -> 114; -march=native measured no faster than x86-64-v2
# (within the scatter), and a binary built with it stops with an illegal instruction on an
# older CPU (CI runners, the Python wheel), so the shipped default stays x86-64-v2.
# Re-measured 2026-11-23 03:33 UTC after the contact's steady path (min of 3-7 interleaved runs,
# load 2.8): -march=native 4-19 % slower than x86-64-v2 (ns per active subcontact-step: bed 38.7
# vs 32.6, PBR 60.7 vs 55.0, 20-drum column 88.7 vs 84.5, corner block 208 vs 200), x86-64-v3
# likewise. `make CC=clang` builds cleanly and gives the same results to the bit.
# `make OPT="-O3 -march=native"` builds cleanly, but with gcc 12 on an FMA machine it differs
# at round-off (1e-30 at 0.01 s, 5e-11 after 2 s of the rocking bed): the SLP vectoriser fuses the
# quaternion product of engine/integrate.c into vfmaddsub despite -ffp-contract=off (that file
# built with -fno-tree-slp-vectorize gives bit-identical outputs).
# Never -ffast-math: the NaN guards rely on isfinite.
# The step's hot functions are built a second time with AVX2 and no FMA, chosen at load where the
# CPU has it, with the same bits (engine/sim.h, RD_HOT; 2026-11-27, callgrind: 6-15 % fewer
# instructions a step on the corner block, the bed, the PBR and the 20-drum column).
OPT     ?= -O3 -march=x86-64-v2
CFLAGS  ?= $(OPT) -g
# -ffp-contract=off: no fused multiply-adds, so every compiler and -march gives the same
# round-off (clang contracts by default; with FMA a rocking history drifts apart within a second;
# gcc 12's vectoriser at -march=native is the exception noted above)
WFLAGS  := -std=c11 -Wall -Wextra -Werror -ffp-contract=off -D_DEFAULT_SOURCE
PKGCFLAGS = $(shell pkg-config --cflags $(PKGS) 2>/dev/null)
PKGLIBS   = $(shell pkg-config --libs $(PKGS) 2>/dev/null) -lhdf5_hl
SUNLIBS := -lsundials_cvode -lsundials_nvecserial -lsundials_sunmatrixdense -lsundials_sunlinsoldense
# position-independent (one set of objects makes both libraries); only RD_API functions
# (include/rockdem/api.h) are visible outside the library
LIBFLAGS := -fPIC -fvisibility=hidden
# OpenMP (gcc's libgomp): one run on several threads (`--set model.threads=N` or
# OMP_NUM_THREADS; engine/workers.c). `make OPENMP=` builds without it (every run serial).
OPENMP  ?= -fopenmp
ALL_CFLAGS = $(WFLAGS) $(CFLAGS) $(SAN) $(OPENMP) $(LIBFLAGS) -Iinclude -Isrc $(PKGCFLAGS)
LDLIBS  = $(PKGLIBS) $(SUNLIBS) -lqhull_r -lm $(OPENMP)

BUILD   ?= build
BIN     ?= bin
# the engine library: every concept folder of src/ but the command-line program (src/cli/)
LIBSRC  := $(filter-out src/cli/%,$(wildcard src/*/*.c))
LIBOBJ  := $(LIBSRC:src/%.c=$(BUILD)/obj/%.o)
CLISRC  := $(filter-out src/cli/main.c src/cli/rockdem_mpi.c,$(wildcard src/cli/*.c))
CLIOBJ  := $(CLISRC:src/%.c=$(BUILD)/obj/%.o)
TESTSRC := $(wildcard tests/test_*.c)
TESTBIN := $(TESTSRC:tests/%.c=$(BUILD)/tests/%)
HEADERS := $(wildcard include/rockdem/*.h src/*/*.h tests/*.h)
DEPS_STAMP := $(BUILD)/.deps-ok

.PHONY: python all lib run test unit asan asan-unit debug fragility-example fuzz fuzz-bins bench bench-study bench-echo-cliff bench-safety bench-fragility-step bench-peers study deps clean check-yade mpi

all: $(BIN)/rockdem $(BUILD)/librockdem.so

# the engine library alone, static and shared (an embedding program or Python's ctypes)
lib: $(BUILD)/librockdem.a $(BUILD)/librockdem.so

# docs/examples/embed.c: a scene run through the public API alone, no file (docs/ARCHITECTURE.md)
examples: $(BUILD)/embed
$(BUILD)/embed: docs/examples/embed.c $(BUILD)/librockdem.a $(HEADERS)
	$(CC) $(WFLAGS) $(CFLAGS) $(SAN) -Iinclude $< $(BUILD)/librockdem.a $(LDLIBS) -o $@

deps: $(DEPS_STAMP)
$(DEPS_STAMP): tools/install-deps.sh
	@bash tools/install-deps.sh
	@mkdir -p $(dir $@) && touch $@

$(BUILD)/obj/%.o: src/%.c $(HEADERS) | $(DEPS_STAMP)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -c $< -o $@

# librockdem.a: one relocatable object in which the hidden symbols (everything but RD_API) are
# made local, so the static library exports what the shared one does and a helper of one folder
# cannot clash with a user's symbol
$(BUILD)/rockdem.o: $(LIBOBJ)
	ld -r -o $@ $^
	objcopy --localize-hidden $@

$(BUILD)/librockdem.a: $(BUILD)/rockdem.o
	@mkdir -p $(dir $@)
	rm -f $@ && ar rcs $@ $^

$(BUILD)/librockdem.so: $(LIBOBJ)
	$(CC) -shared -Wl,-soname,librockdem.so $(CFLAGS) $(SAN) $^ $(LDLIBS) -o $@

# the unit tests reach private headers (geometry/geom.h, engine/sim.h): they link every object
$(BUILD)/librockdem-internal.a: $(LIBOBJ)
	rm -f $@ && ar rcs $@ $^

$(BIN)/rockdem: src/cli/main.c $(CLIOBJ) $(BUILD)/librockdem.a $(HEADERS)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) src/cli/main.c $(CLIOBJ) $(BUILD)/librockdem.a $(LDLIBS) -o $@

$(BUILD)/tests/%: tests/%.c $(BUILD)/librockdem-internal.a $(HEADERS)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) $< $(BUILD)/librockdem-internal.a $(LDLIBS) -lcmocka -o $@

# the program with the contact's steady path switched off (every point through the general
# law): tests/cli/steady_path.sh checks that its outputs equal bin/rockdem's to the bit
$(BUILD)/obj-general/engine/contact.o: src/engine/contact.c $(HEADERS) | $(DEPS_STAMP)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -DRD_STEADY_PATH=0 -c $< -o $@

$(BUILD)/tests/rockdem-general: src/cli/main.c $(CLIOBJ) $(filter-out $(BUILD)/obj/engine/contact.o,$(LIBOBJ)) $(BUILD)/obj-general/engine/contact.o $(HEADERS)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) src/cli/main.c $(filter %.o,$^) $(LDLIBS) -o $@

# the program with every loop threaded however small the scene (engine/workers.c:
# RD_ITEMS_PER_THREAD 0): tests/cli/threads.sh checks that its outputs on 1 and more threads are
# bin/rockdem's to the bit
$(BUILD)/obj-threads/engine/workers.o: src/engine/workers.c $(HEADERS) | $(DEPS_STAMP)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -DRD_ITEMS_PER_THREAD=0 -c $< -o $@

$(BUILD)/tests/rockdem-threads: src/cli/main.c $(CLIOBJ) $(filter-out $(BUILD)/obj/engine/workers.o,$(LIBOBJ)) $(BUILD)/obj-threads/engine/workers.o $(HEADERS)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) src/cli/main.c $(filter %.o,$^) $(LDLIBS) -o $@

# also the shipped PBR's mesh, so the README's next commands (scenarios/pbr.dat) run as written
run: $(BIN)/rockdem scenarios/pbr.obj
	$(BIN)/rockdem run scenarios/default.dat

# the shipped PBR's mesh comes from a seeded generator (no mesh is committed)
scenarios/pbr.obj: tools/make_pbr.py
	/usr/bin/python3 tools/make_pbr.py --seed 1 -o $@

# the worked example of docs/FRAGILITY.md: PBR planes, rose and modes; a calibration (~4 min)
fragility-example: $(BIN)/rockdem scenarios/pbr.obj
	bash tools/fragility_example.sh $(BIN)/rockdem

test: $(BIN)/rockdem $(BUILD)/librockdem.a $(BUILD)/librockdem.so $(BUILD)/embed $(TESTBIN) $(BUILD)/tests/rockdem-general $(BUILD)/tests/rockdem-threads scenarios/pbr.obj
	@bash tests/run.sh $(BUILD) $(BIN)

# the full validation ladder (tools/validate/ladder.py; `make test` runs its fast depth): writes
# docs/validation.md, a generated report (never edit it by hand). About 10-15 min on 2 cores.
.PHONY: validate
validate: $(BIN)/rockdem
	/usr/bin/python3 tools/validate/ladder.py --depth full --bin $(BIN)/rockdem --md docs/validation.md \
	    --json $(BUILD)/validate/results.json

# the same ladder with every DEM run under the opt-in surface contact model (ladder.py --contact
# surface: docs/CONTACT.md section 8): writes docs/validation-surface.md, a generated report.
# Its fast depth (the committed report; about 5 min on 2 cores) is the default: the full depth
# (`make validate-surface SURFACE_DEPTH=full`) takes many times longer.
SURFACE_DEPTH ?= fast
.PHONY: validate-surface
validate-surface: $(BIN)/rockdem
	/usr/bin/python3 tools/validate/ladder.py --depth $(SURFACE_DEPTH) --contact surface --bin $(BIN)/rockdem \
	    --md docs/validation-surface.md --json $(BUILD)/validate/results-surface.json

# AddressSanitizer and UBSan, with the internal invariants checked (RD_DEBUG: base/assert.h).
# `make asan` runs every test so built; `make asan-unit` the CMocka unit tests only (.ci/run).
ASAN_VARS := BUILD=build-asan BIN=build-asan/bin OPT=-O1 \
    SAN="-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all -DRD_DEBUG"
asan:
	$(MAKE) test $(ASAN_VARS)
asan-unit:
	$(MAKE) unit $(ASAN_VARS)

# the CMocka unit tests alone (tests/test_*.c), counted as make test counts them
unit: $(TESTBIN) scenarios/pbr.obj
	@RD_TESTS=unit bash tests/run.sh $(BUILD) $(BIN)

# an optimised build with the internal invariants checked
debug:
	$(MAKE) test BUILD=build-debug BIN=build-debug/bin SAN=-DRD_DEBUG

# libFuzzer (clang) under ASan/UBSan on the readers of untrusted input: tests/fuzz/README.md.
# FUZZ_TIME seconds per target (scenario obj ply stl at2 csv); crashes land in tests/fuzz/found/
FUZZ_TIME    ?= 60
FUZZ_TARGETS := scenario obj ply stl at2 csv
FUZZ_SAN     := -fsanitize=fuzzer-no-link,address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all
fuzz:
	$(MAKE) fuzz-bins BUILD=build-fuzz CC=clang OPT=-O1 SAN="$(FUZZ_SAN)" OPENMP=
	@bash tests/fuzz/run.sh build-fuzz/fuzz $(FUZZ_TIME) $(FUZZ_TARGETS)
fuzz-bins: $(FUZZ_TARGETS:%=$(BUILD)/fuzz/fuzz_%)
$(BUILD)/fuzz/fuzz_%: tests/fuzz/fuzz_target.c $(BUILD)/librockdem-internal.a $(HEADERS)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -fsanitize=fuzzer -DRD_FUZZ_TARGET='"$*"' $< $(BUILD)/librockdem-internal.a $(LDLIBS) -o $@

# the reference point kernel (bench/kernel.c): built with rockdem's own flags, and with the
# flags under which GCC vectorises its structure-of-arrays loop
KERNEL_NATIVE := -O3 -march=native -fno-math-errno
$(BUILD)/bench/kernel: bench/kernel.c
	@mkdir -p $(dir $@)
	$(CC) $(WFLAGS) $(CFLAGS) $< -lm -o $@
$(BUILD)/bench/kernel-native: bench/kernel.c
	@mkdir -p $(dir $@)
	$(CC) $(WFLAGS) $(KERNEL_NATIVE) -g $< -lm -o $@

# about 5-8 min on 2 cores: kernel ratios, the YADE block and multi-body scenes, drum columns
bench: $(BIN)/rockdem $(BUILD)/bench/kernel $(BUILD)/bench/kernel-native scenarios/pbr.obj
	@bash bench/kernel.sh $(BIN) $(BUILD)/bench
	@bash bench/run.sh $(BIN)
	@bash bench/impact_cost.sh $(BIN)
	@bash bench/columns.sh $(BIN)

# a seed-002-sized PBR study (582 runs of 20 s records) timed on a 12-run sample on all cores,
# projected to 2 cores: bench/pbr_study.sh (about 2-4 min on 2 idle cores)
bench-study: $(BIN)/rockdem scenarios/pbr.obj
	@bash bench/pbr_study.sh $(BIN)

# an Echo Cliff-sized PBR study (seed 000: 140 records x 19 PGA levels x 8 directions = 21,280
# runs of 20 s records) timed on a 76-run sample, projected to 2 cores (about 3-6 min on 2 idle cores)
bench-echo-cliff: $(BIN)/rockdem scenarios/pbr.obj
	@STUDY=echo-cliff bash bench/pbr_study.sh $(BIN)

# how the step moves a PBR fragility study's outcomes and fitted medians, against a 0.01 deg turn
# of the shaking (about 15 min on 2 cores; docs/FRAGILITY.md)
bench-fragility-step: $(BIN)/rockdem scenarios/pbr.obj
	@bash bench/fragility_step.sh $(BIN)

# the step's safety factor by time to solution: the fast ladder and the PBR study's cost per run
# at each factor of SAFETIES (bench/safety.sh, about 10-15 min per factor on 2 idle cores)
bench-safety: $(BIN)/rockdem scenarios/pbr.obj
	@bash bench/safety.sh $(BIN)

# time to solution at equal accuracy against PyBullet and MuJoCo (pip, into $(BUILD)/peers-venv;
# skipped with the reason when offline) and YADE (Debian): bench/peers.sh, about 10-20 min
bench-peers: $(BIN)/rockdem
	@bash bench/peers.sh $(BIN) $(BUILD)

# regenerate the stored YADE runs in tests/data/yade/ (dt) and tests/data/yade/half/ (dt/2) and
# compare (needs yade: `apt-get install yade`, ~1.5 GB); docs/YADE.md
check-yade: $(BIN)/rockdem
	/usr/bin/python3 tools/yade/regen.py
	/usr/bin/python3 tools/validate/ladder.py --depth full --only yade,column --bin $(BIN)/rockdem

# every generated block of the docs (sample outputs, the worked example's table and timings,
# the contact tables, CPU times; tools/docgen.py, about 5 min on 2 cores), docs/validation.md
# from the last `make validate` results file, the performance tables from the last
# `make docs-bench` outputs, the figures (tools/doc_figures.sh) and the fragility worked
# example's figures (docs/fragility/, tools/fragility_example.sh: about 1 min). `make test` checks
# the blocks and tools/doc_figures.sh's figures (tests/cli/docs_current.sh). The runout example's
# figures (docs/runout/) come from its own runs: scenarios/runout/run.sh (30 min or more).
.PHONY: docs docs-bench docs-validation
docs: $(BIN)/rockdem $(BUILD)/librockdem.so scenarios/pbr.obj
	@/usr/bin/python3 tools/docgen.py write --bin $(BIN)/rockdem
	@bash tools/fragility_example.sh $(BIN)/rockdem > /dev/null
# rerun `make bench` and `make bench-study` (about 15 min) into $(BUILD)/bench/out, then write
# docs/PERFORMANCE.md's tables from them
docs-bench: $(BIN)/rockdem $(BUILD)/bench/kernel $(BUILD)/bench/kernel-native scenarios/pbr.obj
	@bash bench/docs_bench.sh $(BIN) $(BUILD)
	@/usr/bin/python3 tools/docgen.py write perf-kernel perf-yade perf-impact perf-columns perf-study --bin $(BIN)/rockdem
# rerun `make validate` (10-15 min), then write docs/validation.md from its results file
docs-validation: validate
	@/usr/bin/python3 tools/docgen.py write validation --bin $(BIN)/rockdem

# error against run time of the DEM vs the rigid references: docs/study.md, docs/study.png
study: $(BIN)/rockdem
	@bash bench/study.sh $(BIN)

# bin/rockdem-mpi: `mpirun -n N rockdem-mpi sweep ...` (docs/FRAGILITY.md); needs mpicc
# (Debian libopenmpi-dev, openmpi-bin); the normal build does not
MPICC ?= mpicc
mpi: $(BIN)/rockdem-mpi
$(BIN)/rockdem-mpi: src/cli/rockdem_mpi.c $(CLIOBJ) $(BUILD)/librockdem.a $(HEADERS)
	@mkdir -p $(dir $@)
	$(MPICC) $(ALL_CFLAGS) $< $(CLIOBJ) $(BUILD)/librockdem.a $(LDLIBS) -o $@

# the C style of .clang-format (Debian clang-format 14) applied in place
FORMAT_FILES = $(wildcard src/*/*.c src/*/*.h include/rockdem/*.h tests/*.c tests/*.h tests/fuzz/*.c docs/examples/*.c bench/*.c)
.PHONY: format
format:
	clang-format -i $(FORMAT_FILES)

clean:
	rm -rf build build-asan build-debug build-fuzz bin

# the Python module (tools/rockdem, docs/examples/pbr_study.py): its library and the rockdem
# program beside it, so `pip install ./tools` packs them (tools/pyproject.toml)
# the Python API reference, built from the docstrings and type hints by the standard library's
# pydoc (nothing to install): one HTML page per module in $(BUILD)/python-docs/ (docs/PYTHON.md)
PYDOC_MODULES := rockdem rockdem.scenario rockdem.simulation rockdem.scene rockdem.results
.PHONY: python-docs
python-docs: $(BUILD)/librockdem.so
	@mkdir -p $(BUILD)/python-docs
	cd $(BUILD)/python-docs && PYTHONPATH=$(abspath tools) ROCKDEM_LIB=$(abspath $(BUILD))/librockdem.so \
	    /usr/bin/python3 -m pydoc -w $(PYDOC_MODULES)
	@echo "API reference: $(BUILD)/python-docs/rockdem.html"

python: $(BUILD)/librockdem.so $(BIN)/rockdem
	@mkdir -p tools/rockdem/bin
	cp $(BUILD)/librockdem.so tools/rockdem/librockdem.so
	cp $(BIN)/rockdem tools/rockdem/bin/rockdem
