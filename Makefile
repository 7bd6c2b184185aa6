# polycube: the two commands a user needs are `make demo` and `make test`;
# both install what is missing (Debian 12 packages), build, then run.

PYTHON  ?= /usr/bin/python3
BLENDER ?= blender
BUILD   ?= build
JOBS    ?= 2
VERSION := $(shell sed -n 's/^version *= *"\(.*\)"/\1/p' blender_manifest.toml 2>/dev/null)

# Debian packages the build, the tests and the demo need.
DEB_PACKAGES := cmake g++ make pkg-config libeigen3-dev pybind11-dev python3-dev libboost-graph-dev \
  python3-numpy python3-pytest python3-scipy libgtest-dev libosd-dev \
  libsuitesparse-dev libopenblas0-pthread libcgal-demo blender xvfb xauth zip clang libclang-rt-dev \
  nlohmann-json3-dev libcli11-dev

MESHES := $(BUILD)/data/meshes
SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)

FUZZ_SECONDS ?= 60
FUZZ_BUILD   ?= build-fuzz

.PHONY: all deps build data test test-native test-python test-blender demo package bench fuzz clean

all: build

deps:
	@missing=$$(for p in $(DEB_PACKAGES); do dpkg-query -W -f='$${Status}\n' $$p 2>/dev/null | grep -q '^install ok installed' || echo $$p; done); \
	if [ -n "$$missing" ]; then \
	  echo "Installing Debian packages:" $$missing; \
	  $(SUDO) apt-get update -qq && DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq $$missing; \
	else echo "All Debian packages present."; fi

# The CHOLMOD plugin is copied where it was built, tested in the shell: make
# expands a whole recipe before its first line has built anything.
build: deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release -DPYTHON_EXECUTABLE=$(PYTHON) --log-level=WARNING
	cmake --build $(BUILD) -j $(JOBS)
	cp $(BUILD)/polycube_native*.so addon/
	if [ -f $(BUILD)/polycube_cholmod.so ]; then cp $(BUILD)/polycube_cholmod.so addon/; fi

# Real models from Debian's libcgal-demo, unpacked once (not committed).
data: $(MESHES)/fandisk.off
$(MESHES)/fandisk.off:
	mkdir -p $(BUILD)
	tar xzf /usr/share/doc/libcgal-dev/data.tar.gz -C $(BUILD) data/meshes
	touch $@

test: build data test-native test-python test-blender

test-native:
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

test-python:
	PYTHONPATH=$(BUILD) POLYCUBE_BUILD=$(BUILD) $(PYTHON) -m pytest -q tests/python

test-blender: package
	@$(MAKE) --no-print-directory data
	$(PYTHON) tests/blender/run.py --blender $(BLENDER) --zip dist/polycube-$(VERSION).zip

demo: build data
	$(BLENDER) -b --factory-startup --python addon/headless.py -- --iterations 200 --animate \
	  --output $(BUILD)/demo/sphere.blend --preview $(BUILD)/demo/sphere.png --report $(BUILD)/demo/sphere.json
	$(BLENDER) -b --factory-startup --python addon/headless.py -- --input $(MESHES)/fandisk.off --iterations 100 \
	  --output $(BUILD)/demo/fandisk.blend --preview $(BUILD)/demo/fandisk.png --report $(BUILD)/demo/fandisk.json

package: build
	rm -rf $(BUILD)/package dist/polycube-$(VERSION).zip && mkdir -p $(BUILD)/package dist
	cp -r addon $(BUILD)/package/polycube
	cp blender_manifest.toml README.md $(BUILD)/package/polycube/
	rm -rf $(BUILD)/package/polycube/lib
	$(PYTHON) packaging/bundle_libraries.py $(BUILD)/package/polycube/polycube_*.so $(BUILD)/package/polycube/lib
	find $(BUILD)/package -name __pycache__ -prune -exec rm -rf {} +
	cd $(BUILD)/package && zip -qr ../../dist/polycube-$(VERSION).zip polycube
	@echo "Wrote dist/polycube-$(VERSION).zip"

# The readers, the validator and the deformation under AddressSanitizer and
# UBSan, fed by libFuzzer (clang) from tests/fuzz/seeds for FUZZ_SECONDS. The
# corpus it grows stays in $(FUZZ_BUILD)/corpus for the next run; an input
# that fails is saved in $(FUZZ_BUILD)/crashes/: fix the bug, then copy the
# input to tests/fuzz/regressions/, which `make test` replays.
fuzz: deps
	CXX=clang++ cmake -S . -B $(FUZZ_BUILD) -DPOLYCUBE_FUZZ=ON -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_FLAGS="-O1 -gline-tables-only" \
	  -DCMAKE_DISABLE_FIND_PACKAGE_OpenMP=ON --log-level=WARNING
	cmake --build $(FUZZ_BUILD) -j $(JOBS) --target polycube_fuzz
	mkdir -p $(FUZZ_BUILD)/corpus $(FUZZ_BUILD)/crashes
	for seed in tests/fuzz/seeds/*; do \
	  case $$seed in *.off) format='\000';; *.obj) format='\001';; *) format='\002';; esac; \
	  { printf "$$format"; cat "$$seed"; } > $(FUZZ_BUILD)/corpus/seed-$$(basename $$seed); \
	done
	@echo "Fuzzing for $(FUZZ_SECONDS) s (log: $(FUZZ_BUILD)/fuzz.log)"
	@if UBSAN_OPTIONS=print_stacktrace=1 $(FUZZ_BUILD)/polycube_fuzz -max_total_time=$(FUZZ_SECONDS) \
	     -max_len=4096 -timeout=30 -rss_limit_mb=4096 -print_final_stats=1 \
	     -artifact_prefix=$(FUZZ_BUILD)/crashes/ $(FUZZ_BUILD)/corpus tests/fuzz/regressions \
	     > $(FUZZ_BUILD)/fuzz.log 2>&1; then \
	  grep -E '^#[0-9]+[[:space:]]+(INITED|DONE)|^Done|^stat::' $(FUZZ_BUILD)/fuzz.log; \
	else tail -80 $(FUZZ_BUILD)/fuzz.log; ls -l $(FUZZ_BUILD)/crashes; exit 1; fi

# Speed, memory and ratios against the paper-literal variant and a SciPy
# reference, on real models and their ~1M-triangle refinements (not part of test);
# QUICK=1: the models at their own size only. Every run is bounded; the table
# (build/bench/results.md, .json) is written after every row.
bench: build data
	$(PYTHON) tests/benchmark/bench.py --build $(BUILD) $(if $(QUICK),--quick)

clean:
	rm -rf $(BUILD) $(FUZZ_BUILD) dist addon/*.so
