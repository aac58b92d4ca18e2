# Stratum: the two commands of the README (`make render`, `make test`) and their parts.
# Every target installs what it needs first (scripts/setup.sh is idempotent).

BUILD      ?= build
VENV       := .venv
PY         := $(VENV)/bin/python
BLENDER    ?= blender
BLENDER_BG := $(BLENDER) -b --factory-startup -noaudio
# A module of scripts/ inside Blender: `$(BLENDER_RUN) scripts.bench.speed ARGS` (the launcher puts
# this checkout on Blender's sys.path); the venv's Python runs them as `$(PY) -m scripts.<room>.<module>`.
BLENDER_RUN := $(BLENDER_BG) --python scripts/run_in_blender.py --
CMAKE_ARGS ?= -DCMAKE_BUILD_TYPE=Release -DSTRATUM_WERROR=ON
LIB        := addon/stratum/lib/libstratum.so

.PHONY: all setup build check test test-native test-native-statistical test-python test-blender test-blender-3 test-blender-wheel \
        lint render bench sanitize format clean study test-corpus test-sessions test-ui corpus-asan \
        settings-table package test-package test-wheels

all: build

setup:
	bash scripts/setup.sh

build: setup
	cmake -S . -B $(BUILD) -G Ninja $(CMAKE_ARGS) > $(BUILD).configure.log || (cat $(BUILD).configure.log; false)
	cmake --build $(BUILD)
	mkdir -p addon/stratum/lib
	# Copy then rename: overwriting the file in place would crash a process that has it loaded.
	cp -f $(BUILD)/libstratum.so $(LIB).tmp && mv -f $(LIB).tmp $(LIB)
	# Open Image Denoise beside it (Blender 3.4's Python does not see the venv's pyoidn).
	$(PY) -m scripts.packaging.copy_oidn addon/stratum/lib

# The fast tier for iterating on a change (README, "Other targets"; about 6 min on 2 idle cores
# from a built tree): lint, the C++ suite but for its tests labelled `long` (CMakeLists.txt), the
# Python suite but for its tests marked `long`, and the Blender tests marked `smoke`
# (tests/blender/conftest.py) in the bpy wheel. `make test` runs all of these and the rest.
check: build lint
	cd $(BUILD) && ctest --output-on-failure -j2 -LE long
	$(PY) -m pytest tests/python -q -m "not long"
	$(PY) -m pytest tests/blender -q -m smoke

# The slowest tests of each pytest stage, printed at its end: where make test's 45 minutes go.
DURATIONS ?= --durations=15 --durations-min=5
# corpus-asan after sanitize, which builds the binary it replays with.
test: build lint test-native-statistical test-python test-blender test-wheels test-package test-ui sanitize corpus-asan \
      fuzz-smoke

test-native: build
	cd $(BUILD) && ctest --output-on-failure -j2

# What make test runs of the C++ suite in this Release build: the statistical tests, labelled
# `long` or left out of the sanitizer run (SANITIZE_SKIP). Every other native test runs in make
# sanitize's build under ASan and UBSan, at -O2, which make test runs too; make check and make
# test-native run them all in Release.
test-native-statistical: build
	cd $(BUILD) && ctest --output-on-failure -j2 -L long
	cd $(BUILD) && ctest --output-on-failure -j2 -LE long -R '$(SANITIZE_SKIP)'

test-python: build
	$(PY) -m pytest tests/python -q $(DURATIONS)

# The same Blender tests in Blender 3.4 (Debian, `blender -b`) and in the bpy wheel (4.5/5.0).
test-blender: test-blender-3 test-blender-wheel test-corpus test-sessions

test-blender-3: build
	$(BLENDER_BG) --python tests/blender/run_in_blender.py -- tests/blender -q $(DURATIONS)

test-blender-wheel: build
	$(PY) -m pytest tests/blender -q $(DURATIONS)

# The smoke matrix of the LTS lines (issue 33): the bpy 4.2 and 4.5 wheels, one venv per
# scripts/requirements-bpy-<line>.txt (scripts/setup_wheels.sh, run by scripts/setup.sh): the
# Cornell box and every feature scene against that version's Cycles, every shader node, the Bump
# node's shadowing and the lights per pixel against it (docs/blender_versions.md: about 13 s of
# the three per line), and that version's image-hash table. Through run_in_blender.py, which
# leaves with os._exit: the 4.5 wheel's process can hang at exit in bpy's own delayed-close
# thread. A failing line does not stop the other.
WHEEL_LINES := $(patsubst scripts/requirements-bpy-%.txt,%,$(wildcard scripts/requirements-bpy-*.txt))
WHEEL_TESTS := tests/blender/test_cycles_agreement.py tests/blender/test_feature_agreement.py \
               tests/blender/test_node_agreement.py tests/blender/test_bump_agreement.py \
               tests/blender/test_light_agreement.py tests/blender/test_image_hashes.py
test-wheels: build
	status=0; for line in $(WHEEL_LINES); do \
		echo "== bpy $$line wheel"; \
		.venv-bpy-$$line/bin/python tests/blender/run_in_blender.py -- $(WHEEL_TESTS) -q $(DURATIONS) || status=1; \
	done; exit $$status

# The zip users install (docs/packaging.md): dist/stratum-<version>-linux-x64.zip, the add-on
# with libstratum.so and every library it needs beyond the base system.
package: build
	$(PY) -m scripts.packaging.package --library $(BUILD)/libstratum.so --out dist

# Builds the package twice (this version and the next, for the upgrade) from build/, installs it
# into fresh user configurations of Blender 3.4 and of the bpy wheels (5.0, 4.2, 4.5), renders,
# upgrades, uninstalls (tests/package). ~2 min.
test-package: build
	$(PY) -m pytest tests/package -q $(DURATIONS)

# Blender 3.4 with its UI on a virtual display (xvfb-run): the Rendered viewport as a user
# drives it, and what must not crash it (tests/ui). ~5 min.
test-ui: build
	$(PY) -m pytest tests/ui -q $(DURATIONS)

# The hostile-scene corpus (issue 12): every case in Blender 3.4 and in the bpy wheel, each in
# worker subprocesses so that a crash fails one case; table in out/corpus/outcomes.md. ~30 s.
test-corpus: build
	BLENDER=$(BLENDER) $(PY) -m pytest tests/blender/corpus -q

# Long sessions (200 renders, resident memory) and cancel latency, each Blender in a fresh
# process. ~30 s.
test-sessions: build
	$(BLENDER_BG) --python tests/blender/run_in_blender.py -- tests/blender/session -q
	$(PY) -m pytest tests/blender/session -q

# The native part of the corpus under a sanitizer build: every case's scene captured through the
# bpy wheel and rendered again by $(CORPUS_NATIVE) (default: the CLI of `make sanitize`'s
# build); fails on a sanitizer report, an assertion or a non-finite pixel. Table in
# out/corpus-native/replay.md.
CORPUS_NATIVE ?= $(BUILD)-asan/stratum-native
corpus-asan: build
	@test -x "$(CORPUS_NATIVE)" || { echo "corpus-asan: no $(CORPUS_NATIVE): run make sanitize or set CORPUS_NATIVE"; false; }
	BLENDER=$(BLENDER) PYTHONPATH=tests/blender $(PY) -m corpus.replay $(CORPUS_NATIVE)

lint: setup
	$(VENV)/bin/ruff check addon tests scenes scripts native/fuzz/tools
	clang-format --dry-run -Werror $$(git ls-files 'native/*.cpp' 'native/*.h' 'tests/native/*.cpp' 'tests/native/*.h')

format: setup
	clang-format -i $$(git ls-files 'native/*.cpp' 'native/*.h' 'tests/native/*.cpp' 'tests/native/*.h')
	$(VENV)/bin/ruff check --fix addon tests scenes scripts native/fuzz/tools

# README.md's render-settings tables, written anew from the library's list of settings.
settings-table: build
	$(PY) -m scripts.settings_table

# Renders the bundled Cornell box with Stratum through Blender in background mode.
render: build
	bash scripts/install_addon.sh
	mkdir -p out
	$(BLENDER) -b scenes/cornell_box.blend --addons stratum -E STRATUM \
		--python scripts/run_in_blender.py -- scripts.render.render_to_files out/cornell_box
	@echo "Stratum rendered the Cornell box: $(CURDIR)/out/cornell_box.png (display) and $(CURDIR)/out/cornell_box.exr (linear)"

# The micro-benchmarks of native/bench (docs/performance.md, "Micro-benchmarks"): items/s of
# samplers, closures, light samples, the spherical triangle and the film, in
# out/microbench.txt and out/microbench.json.
.PHONY: microbench
# Where the path tracer spends its time: perf over a captured Cornell box (docs/performance.md).
.PHONY: profile
profile: build
	bash scripts/render/profile_render.sh max_bounces=8

microbench: build
	mkdir -p out
	$(BUILD)/stratum_microbench --benchmark_out=out/microbench.json --benchmark_out_format=json > out/microbench.txt \
		|| (cat out/microbench.txt; false)
	cat out/microbench.txt

# Issue 15's sections (scripts/bench/) write out/bench/*.json; summary.py prints them as one table
# (also out/bench_summary.txt) at the end.
bench: build microbench
	bash scripts/install_addon.sh
	mkdir -p out
	rm -rf out/bench
	$(BLENDER_RUN) scripts.bench.speed
	$(BLENDER_RUN) scripts.bench.samplers
	$(BLENDER_RUN) scripts.bench.quality
	$(BLENDER_RUN) scripts.bench.adaptive
	$(BLENDER_RUN) scripts.bench.memory
	$(BLENDER_RUN) scripts.bench.progress
	$(PY) -m scripts.bench.textures
	$(BLENDER_RUN) scripts.bench.shader_nodes
	$(PY) -m scripts.bench.distributed_render
	$(BLENDER_RUN) scripts.bench.viewport
	xvfb-run -a -s "-screen 0 1280x800x24" $(BLENDER) scenes/cornell_box.blend --factory-startup -noaudio --window-geometry 0 0 800 600 --python scripts/run_in_blender.py -- scripts.bench.viewport_ui out/bench_viewport_ui && test -s out/bench_viewport_ui.txt
	$(PY) -m scripts.bench.summary

# The study: the sampler runs of issue 4 (Cornell box, Wolf, AO; 24.6 min measured on 2 shared
# cores) and the estimator ladder of issue 6 (small-light, large-light and glossy Cornell boxes;
# 30 min measured under load, 9.3 min on a quiet machine), `stratum compare` runs into
# out/study/, then out/study/summary.md, out/study/estimators.md and figures; the radiosity
# solvers of issue 17 (scripts/study/radiosity.py, seconds) into out/study/radiosity.md, and path
# guiding against Cycles' (scripts/study/guiding.py, run by run.py: about 7 min) into
# out/study/guiding.md. Not part of `make test`. Re-running renders only what is missing.
study: build
	$(PY) -m scripts.study.auto_lights --out out/study
	$(PY) -m scripts.study.radiosity --out out/study
	$(PY) -m scripts.bench.quality --scene many_lights_hall --sampler sobol --res 96 --samples 32 \
		--reference-samples 1024 --light-selection tree,tree:1,power,uniform,mixed --section quality_lights
	$(PY) -m scripts.study.run --out out/study --jobs 2

# One clang build with ASan, UBSan (findings abort) and libFuzzer coverage serves the sanitized
# test suite and the ABI fuzzer (native/fuzz/README.md).
.PHONY: build-sanitize fuzz fuzz-smoke
FUZZ_BUILD    ?= $(BUILD)-asan
FUZZ_SECONDS  ?= 600
FUZZ_JOBS     ?= 1
SANITIZER_ENV := LSAN_OPTIONS=suppressions=$(CURDIR)/native/fuzz/lsan.supp UBSAN_OPTIONS=print_stacktrace=1

build-sanitize: setup
	cmake -S . -B $(FUZZ_BUILD) -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
		"-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -gline-tables-only" -DSTRATUM_FUZZ=ON \
		> $(FUZZ_BUILD).configure.log || (cat $(FUZZ_BUILD).configure.log; false)
	cmake --build $(FUZZ_BUILD)

# Every C++ test under ASan+UBSan, with the fuzzer's seed corpus and regression inputs replayed,
# but for SANITIZE_SKIP: convergence tests whose subject is a statistic (many seeds or samples
# against a closed form, a chi-square or a quadrature), which the Release build of test-native
# runs, and which take 4-7x as long under the sanitizers: the adaptive closed sphere 238 s, the
# panel two centimetres away 39 s, the light tree's pmf against its frequencies 31 s, the
# closures' and the BSDFs' chi-squares 66 s and 29 s, and 10-16 s each for the rest (measured in
# a fresh-clone run of make test, 2 cores). Their code paths run under the sanitizers in the same
# suites' shorter tests (AdaptiveSampling.*, ManyLights and LightTreeSplit.*, IntegratingSphere*.*,
# Radiosity*.*, ErrorPass.*, Closures.*, Bsdf.*, Principled.*, EmitterNormalisation.*).
SANITIZE_SKIP := AdaptiveSampling.TheClosedSphereConvergesToItsClosedFormAtTheDefaultThreshold|$\
	ManyLights.EverySelectionModeMatchesTheClosedSum|ManyLights.TreeWithSplittingMatchesTheClosedSum|$\
	IntegratingSphere.EverySamplerIsUnbiased|IntegratingSphereEstimators.EmissiveWallsEveryPathEstimator|$\
	RadiosityIntegrator.CornellBoxBlocksMatchThePathTracerAsPatchesShrink|$\
	ErrorPass.MeasuresWhatThePassMeansForEverySampler|Closures.SamplingMatchesPdfChiSquare|$\
	EmitterNormalisation.EveryWayOfFindingAPanelTwoCentimetresAwayMeasuresTheClosedForm|$\
	LightTreeSplit.PmfMatchesTheFrequenciesOfTheCutsChoices|Bsdf.SamplingMatchesPdfChiSquare|$\
	Bsdf.SampledAlbedoMatchesQuadratureOfEval|Bsdf.WhiteFurnaceEnergyConservingModels|$\
	RadiositySolvers.PortedSphereBStaysInsideTheFormFactorBound|$\
	RadiositySolvers.SphereAIsTextbook317WithinTheTessellationBound|$\
	RadiosityIntegrator.SphereARendersTextbook317|$\
	IntegratingSphere.PortedSphereRadianceIsEmissionOverOneMinusKTimesOneMinusH|$\
	IntegratingSpherePointLight.EverySamplerIsUnbiased|Principled.V2GgxLosesEnergyLikeCycles
sanitize: build-sanitize
	cd $(FUZZ_BUILD) && $(SANITIZER_ENV) ctest --output-on-failure -j2 -E '$(SANITIZE_SKIP)'

# The fuzzer for FUZZ_SECONDS with FUZZ_JOBS workers, collecting every crash in out/fuzz/artifacts.
fuzz: build-sanitize
	$(SANITIZER_ENV) bash native/fuzz/tools/fuzz.sh $(FUZZ_BUILD)/stratum_fuzz $(FUZZ_SECONDS) $(FUZZ_JOBS)

# The bounded run of `make test`: 60 s (it replays the corpus first; `make fuzz` is the long
# run), stops at the first crash.
fuzz-smoke: build-sanitize
	$(SANITIZER_ENV) bash native/fuzz/tools/fuzz.sh $(FUZZ_BUILD)/stratum_fuzz 60 0

# Valgrind memcheck of the native determinism test (every sampler x integrator renders a box 3
# times in one process, threads 1, 2 and 7): uninitialised reads, which ASan/UBSan do not
# report and which could make renders differ. MSan would need TBB, Embree, OpenImageIO and the
# C++ library rebuilt with it; valgrind checks the binaries as they are. (Valgrind 3.19 has no
# AVX-512, so Embree runs its AVX2 kernels under it.) About 1 min on 2 shared cores.
.PHONY: valgrind
valgrind: build
	STRATUM_DETERMINISM_RENDERS=3 valgrind --tool=memcheck --error-exitcode=1 --num-callers=30 \
		$(BUILD)/stratum_tests --gtest_filter='Determinism.EverySamplerAndIntegrator*'

sanitize: valgrind

clean:
	rm -rf $(BUILD) $(BUILD)-asan $(BUILD).configure.log addon/stratum/lib out dist
