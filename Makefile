# The two commands: `make run` and `make test`. Both install the Debian
# packages that are missing, configure a Release build and build it.
SHELL := /bin/bash
BUILD ?= build
ASAN_BUILD ?= build-sanitize
FUZZ_BUILD ?= build-fuzz
NODRACO_BUILD ?= build-nodraco
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
SHARED_DATA ?= $(abspath ../shared/data)

DEBIAN_PACKAGES := cmake make g++ pkg-config ccache xz-utils \
  libcgal-dev libeigen3-dev libopenmesh-dev libdraco-dev libboost-program-options-dev \
  nlohmann-json3-dev libssl-dev zlib1g-dev \
  libgtest-dev libgmock-dev libbenchmark-dev libmeshoptimizer-dev gnuplot-nox \
  help2man dpkg-dev file libtomlplusplus-dev libtbb-dev snakemake
FUZZ_PACKAGES := clang libclang-rt-14-dev
# Peers the benchmarks run as subprocesses: OpenMesh-mkbalancedpm
# (bench_hierarchy) and OpenMesh-Analyzer, the VDPM analyzer (bench_pack's
# .spm anchor). Without them those rows are left out with a note.
# OpenMesh-commandlineSubdivider (same package) makes the scaling meshes, and
# GNU time measures their peak resident set (tests/bench/scaling.sh).
BENCH_PACKAGES := libopenmesh-apps time
# make test-cluster: a single-node Slurm on loopback for the Snakemake workflow.
CLUSTER_PACKAGES := slurm-wlm munge

# Node tools the tests and benchmarks run (tests/npm/package.json: Khronos's
# gltf-validator, gltfpack, @gltf-transform/cli), installed from the committed
# lock into the build folder, never the source tree.
NPM_DIR ?= $(abspath $(BUILD))/npm

CMAKE_FLAGS := -DCMAKE_BUILD_TYPE=Release -DLODBAKE_SHARED_DATA=$(SHARED_DATA) \
  -DLODBAKE_NPM_DIR=$(NPM_DIR)

.PHONY: all deps npm-deps fuzz-deps bench-deps configure build run test test-sanitize test-nodraco fuzz fuzz-run bench \
  bench-heldout bench-attributes bench-scaling \
  format format-check clean install package bake-sample test-cluster

all: build

# Installs what is missing, non-interactively (sudo when not root).
deps:
	@missing=$$(for p in $(DEBIAN_PACKAGES); do \
	  dpkg-query -W -f='$${Status}\n' $$p 2>/dev/null | grep -q 'install ok installed' || echo $$p; done); \
	if [ -n "$$missing" ]; then \
	  echo "lodbake: installing Debian packages:" $$missing; \
	  SUDO=; [ "$$(id -u)" -eq 0 ] || SUDO=sudo; \
	  $$SUDO env DEBIAN_FRONTEND=noninteractive apt-get update -qq && \
	  $$SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends $$missing; \
	fi

# `npm ci` from tests/npm's lock, quiet; skipped when the same lock is
# already installed (the stamp is written only after a complete install).
npm-deps:
	@command -v npm > /dev/null || $(MAKE) --no-print-directory deps DEBIAN_PACKAGES="nodejs npm"
	@command -v npm > /dev/null || { echo "Error: npm is needed for the gltf tests (Debian's nodejs and npm)"; exit 1; }
	@mkdir -p $(NPM_DIR); \
	if ! cmp -s tests/npm/package-lock.json $(NPM_DIR)/installed.lock || [ ! -d $(NPM_DIR)/node_modules ]; then \
	  echo "lodbake: installing the npm test tools into $(NPM_DIR)"; \
	  rm -f $(NPM_DIR)/installed.lock; \
	  cp tests/npm/package.json tests/npm/package-lock.json $(NPM_DIR)/ && \
	  npm ci --prefix $(NPM_DIR) --no-audit --no-fund --loglevel=error > $(NPM_DIR).log 2>&1 \
	    || { cat $(NPM_DIR).log; exit 1; }; \
	  cp tests/npm/package-lock.json $(NPM_DIR)/installed.lock; \
	fi

fuzz-deps:
	@$(MAKE) --no-print-directory deps DEBIAN_PACKAGES="$(DEBIAN_PACKAGES) $(FUZZ_PACKAGES)"

bench-deps:
	@$(MAKE) --no-print-directory deps DEBIAN_PACKAGES="$(DEBIAN_PACKAGES) $(BENCH_PACKAGES)"

configure: deps
	@cmake -S . -B $(BUILD) $(CMAKE_FLAGS) > $(BUILD).configure.log 2>&1 || { cat $(BUILD).configure.log; exit 1; }

build: configure
	cmake --build $(BUILD) -j $(JOBS)

# Bakes the embedded sample end to end and prints a summary.
run: build
	@LODBAKE_BIN=$(BUILD)/tools samples/bake.sh $(BUILD)/sample

test: build npm-deps
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# Unit and fuzz-corpus tests under AddressSanitizer + UndefinedBehaviorSanitizer.
test-sanitize: deps
	@cmake -S . -B $(ASAN_BUILD) -DCMAKE_BUILD_TYPE=Debug -DLODBAKE_SANITIZE=ON \
	  -DLODBAKE_BENCHMARKS=OFF -DLODBAKE_SHARED_DATA=$(SHARED_DATA) > $(ASAN_BUILD).configure.log 2>&1 \
	  || { cat $(ASAN_BUILD).configure.log; exit 1; }
	cmake --build $(ASAN_BUILD) -j $(JOBS)
	cd $(ASAN_BUILD) && ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 \
	  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	  ctest --output-on-failure -j $(JOBS) -L 'unit|fuzz'

# The tools built without the Draco section codec (-DLODBAKE_DRACO_CODEC=OFF)
# and the CLI cases through CTest: cases that need the codec are left out,
# the nodraco_ ones (exit code 5 for Draco sections) run instead.
NODRACO_TOOLS := lodbake-inspect lodbake-pack lodbake-simplify lodbake-hierarchy lodbake-fan \
  lodbake-strips lodbake-replay lodbake_man_pages lodbake-bake dragon_data
test-nodraco: deps
	@cmake -S . -B $(NODRACO_BUILD) $(CMAKE_FLAGS) -DLODBAKE_DRACO_CODEC=OFF -DLODBAKE_BENCHMARKS=OFF \
	  > $(NODRACO_BUILD).configure.log 2>&1 || { cat $(NODRACO_BUILD).configure.log; exit 1; }
	cmake --build $(NODRACO_BUILD) -j $(JOBS) --target $(NODRACO_TOOLS)
	cd $(NODRACO_BUILD) && ctest --output-on-failure -j $(JOBS) -L cli

# Real libFuzzer binaries (clang); run one with e.g.
#   build-fuzz/tests/fuzz/fuzz_container tests/fuzz/corpus/container
fuzz: fuzz-deps
	@cmake -S . -B $(FUZZ_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
	  -DCMAKE_C_COMPILER=clang -DLODBAKE_LIBFUZZER=ON -DLODBAKE_SANITIZE=ON -DLODBAKE_BENCHMARKS=OFF \
	  -DLODBAKE_SHARED_DATA=$(SHARED_DATA) > $(FUZZ_BUILD).configure.log 2>&1 \
	  || { cat $(FUZZ_BUILD).configure.log; exit 1; }
	cmake --build $(FUZZ_BUILD) -j $(JOBS) --target fuzz_targets

# A campaign: every fuzz target for FUZZ_SECONDS, from copies of its seeds;
# fails and lists the inputs when one crashes, leaks or runs out of memory.
FUZZ_SECONDS ?= 60
fuzz-run: fuzz
	tests/fuzz/run_campaign.sh $(FUZZ_BUILD) $(FUZZ_SECONDS)

# Import speed against CGAL, OpenMesh and Draco on the full dragon and
# mid-size meshes (prints ratios; timings are never asserted in tests).
BENCH_MESHES := $(BUILD)/data/dragon_vrip.ply $(SHARED_DATA)/meshes/stanford_bun_zipper.ply \
  $(SHARED_DATA)/meshes/igl_armadillo.obj $(SHARED_DATA)/meshes/cgal_bunny00.off \
  $(SHARED_DATA)/meshes/draco_bunny.stl
# Simplification against meshoptimizer, OpenMesh and CGAL at 50%, 10% and 1%
# of the triangles (time, throughput, Hausdorff and mean error; see
# docs/benchmarks.md). BENCH_RUNS sets the runs per median.
BENCH_RUNS ?= 3
SIMPLIFY_BENCH_MESHES := $(SHARED_DATA)/meshes/stanford_bun_zipper.ply \
  $(SHARED_DATA)/meshes/cgal_armadillo.off $(BUILD)/data/dragon_vrip.ply
# The height guard's check on meshes it was not tuned on: the other clean
# meshes with at least 1,000 triangles (docs/benchmarks.md, "The height
# guard"), errors only (one run), without and with the guard.
HELDOUT_MESHES := $(addprefix $(SHARED_DATA)/meshes/,cgal_ChineseDragon-10kv.off \
  cgal_blobby_3cc.off cgal_bunny00.off cgal_camel.off cgal_cheese.off \
  cgal_elephant-with-holes.off cgal_elephant.off cgal_fandisk.off cgal_knot2.off cgal_man.off \
  cgal_mushroom.off cgal_refined_elephant.off igl_camelhead.off igl_fertility.off \
  c3d_rocker-arm.obj c3d_spot.obj igl_armadillo.obj npm_bunny.obj)
# Progressive-mesh container sizes: raw, compact and Draco against OpenMesh's
# .pm, the streaming paper's vsplit topology and Draco single-rate.
PACK_BENCH_MESHES := $(SIMPLIFY_BENCH_MESHES)
# Every section kind's bytes as its tool writes it and after lodbake-pack
# (raw and --draco), from the tools themselves (tests/bench/pack_sections.sh).
PACK_SECTIONS_MESHES := $(SIMPLIFY_BENCH_MESHES)
# Split DAG and vertex trees (docs/hierarchy-dag-vtrees.md): bunny and full dragon.
DAG_BENCH_MESHES := $(SHARED_DATA)/meshes/stanford_bun_zipper.ply $(BUILD)/data/dragon_vrip.ply
# Balanced vertex hierarchy against OpenMesh-mkbalancedpm (build time,
# depth, <tree-id, node-id> bits, output bytes; docs/benchmarks.md).
HIERARCHY_BENCH_MESHES := $(SHARED_DATA)/meshes/stanford_bun_zipper.ply \
  $(SHARED_DATA)/meshes/cgal_armadillo.off $(BUILD)/data/dragon_vrip.ply
# Strips and the SETS graph: stripifier against meshopt_stripify, SETS sizes,
# the paper's recovery tests (docs/benchmarks.md).
STRIPS_BENCH_MESHES := $(SHARED_DATA)/meshes/stanford_bun_zipper.ply $(BUILD)/data/dragon_vrip.ply
# Whole glTF assets in and out against gltfpack's plain copy (npm gltfpack,
# from npm-deps): every asset of shared/data/assets (docs/benchmarks.md).
ASSET_BENCH_FILES := $(sort $(wildcard $(SHARED_DATA)/assets/*/*.gltf $(SHARED_DATA)/assets/*/*.glb))
# Attribute-aware simplification against gltfpack -si, -sa and meshoptimizer's
# simplifyWithAttributes at 0.5, 0.25 and 0.1, scored by lib/metrics: every
# asset with triangles (Duck.gltf left out: Duck.glb's twin) and the textured
# OBJ meshes (docs/benchmarks.md, "Attributes").
ATTRIBUTE_BENCH_FILES := $(filter-out %/Duck.gltf,$(ASSET_BENCH_FILES)) \
  $(SHARED_DATA)/meshes/c3d_spot.obj
bench: bench-deps build npm-deps
	cmake --build $(BUILD) --target dragon_data bench_import bench_simplify bench_hierarchy \
	  bench_dag bench_fan bench_strips bench_pack bench_section_codecs bench_stream bench_assets \
	  bench_attributes
	$(BUILD)/tests/bench/bench_import $(BENCH_MESHES)
	$(BUILD)/tests/bench/bench_simplify --runs $(BENCH_RUNS) $(SIMPLIFY_BENCH_MESHES)
	$(BUILD)/tests/bench/bench_simplify --runs $(BENCH_RUNS) --height-guard --peers lodbake,meshopt \
	  $(SIMPLIFY_BENCH_MESHES)
	$(BUILD)/tests/bench/bench_simplify --runs $(BENCH_RUNS) --height-guard-factor 3 \
	  --peers lodbake,meshopt $(SIMPLIFY_BENCH_MESHES)
	$(BUILD)/tests/bench/bench_simplify --runs $(BENCH_RUNS) --placement optimal \
	  --peers lodbake,cgal $(SIMPLIFY_BENCH_MESHES)
	$(BUILD)/tests/bench/bench_dag --runs $(BENCH_RUNS) $(DAG_BENCH_MESHES)
	$(BUILD)/tests/bench/bench_dag --runs $(BENCH_RUNS) --balanced $(DAG_BENCH_MESHES)
	$(BUILD)/tests/bench/bench_hierarchy --runs $(BENCH_RUNS) $(HIERARCHY_BENCH_MESHES)
	$(BUILD)/tests/bench/bench_fan --runs $(BENCH_RUNS) $(SIMPLIFY_BENCH_MESHES)
	$(BUILD)/tests/bench/bench_strips --runs $(BENCH_RUNS) $(STRIPS_BENCH_MESHES)
	$(BUILD)/tests/bench/bench_pack --runs $(BENCH_RUNS) $(PACK_BENCH_MESHES)
	tests/bench/pack_sections.sh $(BUILD)/tools $(PACK_SECTIONS_MESHES)
	$(BUILD)/tests/bench/bench_stream --runs $(BENCH_RUNS) --clients 16 \
	  $(SHARED_DATA)/meshes/stanford_bun_zipper.ply
	$(BUILD)/tests/bench/bench_assets --runs 5 $(ASSET_BENCH_FILES)
	$(BUILD)/tests/bench/bench_attributes --runs $(BENCH_RUNS) $(ATTRIBUTE_BENCH_FILES)
	tests/bench/bake_sample.sh $(BUILD)/tools $(SHARED_DATA)
	tests/bench/scaling.sh --levels $(SCALING_LEVELS) $(BUILD)/tools $(BUILD)/tests/bench \
	  $(BUILD)/data/dragon_vrip.ply $(BUILD)/tests/bench/scaling

# The scaling table alone (docs/benchmarks.md, "Scaling"): the dragon
# Loop-subdivided SCALING_LEVELS times (0: 0.9M triangles, 1: 3.5M, 2: 14M,
# 3: 56M), made once into $(BUILD)/tests/bench/scaling; e.g. make
# bench-scaling SCALING_LEVELS=0,1. Level 3 is left out by default: its
# hierarchy run alone takes about 10 GB and half an hour (docs/benchmarks.md,
# "Scaling").
SCALING_LEVELS ?= 0,1,2
bench-scaling: bench-deps build
	cmake --build $(BUILD) --target dragon_data bench_simplify
	tests/bench/scaling.sh --levels $(SCALING_LEVELS) $(BUILD)/tools $(BUILD)/tests/bench \
	  $(BUILD)/data/dragon_vrip.ply $(BUILD)/tests/bench/scaling

# The attribute benchmark alone (docs/benchmarks.md, "Attributes").
bench-attributes: build npm-deps
	cmake --build $(BUILD) --target bench_attributes
	$(BUILD)/tests/bench/bench_attributes --runs $(BENCH_RUNS) $(ATTRIBUTE_BENCH_FILES)

bench-heldout: bench-deps build
	cmake --build $(BUILD) --target bench_simplify
	$(BUILD)/tests/bench/bench_simplify --runs 1 --peers lodbake,meshopt --markdown $(HELDOUT_MESHES)
	$(BUILD)/tests/bench/bench_simplify --runs 1 --peers lodbake,meshopt --markdown --height-guard \
	  $(HELDOUT_MESHES)
	$(BUILD)/tests/bench/bench_simplify --runs 1 --peers lodbake,meshopt --markdown \
	  --height-guard-factor 3 $(HELDOUT_MESHES)
	$(BUILD)/tests/bench/bench_simplify --runs 1 --peers lodbake,cgal --markdown \
	  --placement optimal $(HELDOUT_MESHES)

# The tools, man pages, headers, libraries, CMake package and lodbake.pc
# under PREFIX (docs/install.md); `sudo make install` for a system prefix.
PREFIX ?= /usr/local
install: build
	cmake --install $(BUILD) --prefix $(PREFIX)

# Debian packages lodbake and lodbake-dev into $(BUILD)/packages (CPack).
package: build
	cd $(BUILD) && cpack -G DEB

format:
	clang-format -i $$(git ls-files '*.cpp' '*.h')

format-check:
	clang-format --dry-run -Werror $$(git ls-files '*.cpp' '*.h')

clean:
	rm -rf $(BUILD) $(ASAN_BUILD) $(FUZZ_BUILD) $(BUILD).configure.log $(ASAN_BUILD).configure.log

# The sample recipe over the shared data, every step, into $(BUILD)/baked
# with its cache beside it (docs/tools.md "lodbake-bake"); a rerun bakes
# nothing that did not change.
bake-sample: build
	$(BUILD)/tools/lodbake-bake samples/shared_data.toml --set data=$(SHARED_DATA) \
	  --out $(BUILD)/baked --cache $(BUILD)/bake-cache --keep-going

# The Snakemake workflow submitted through workflow/profiles/slurm to a
# single-node Slurm this target starts on loopback (munged, slurmctld, slurmd
# under $(BUILD)/test-cluster, stopped at the end), its files compared with
# lodbake-bake's; names the stage that failed otherwise. Needs root (slurmd).
test-cluster: build
	@$(MAKE) --no-print-directory deps DEBIAN_PACKAGES="$(DEBIAN_PACKAGES) $(CLUSTER_PACKAGES)"
	tests/cluster/slurm_workflow.sh $(BUILD)/tools . $(SHARED_DATA) $(abspath $(BUILD))/test-cluster
