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
  libsuitesparse-dev libopenblas0-pthread libcgal-demo blender xvfb xauth zip

MESHES := $(BUILD)/data/meshes
SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)

.PHONY: all deps build data test test-native test-python test-blender demo package bench clean

all: build

deps:
	@missing=$$(for p in $(DEB_PACKAGES); do dpkg-query -W -f='$${Status}\n' $$p 2>/dev/null | grep -q '^install ok installed' || echo $$p; done); \
	if [ -n "$$missing" ]; then \
	  echo "Installing Debian packages:" $$missing; \
	  $(SUDO) apt-get update -qq && DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq $$missing; \
	else echo "All Debian packages present."; fi

build: deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release -DPYTHON_EXECUTABLE=$(PYTHON) --log-level=WARNING
	cmake --build $(BUILD) -j $(JOBS)
	cp $(BUILD)/polycube_native*.so addon/

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
	cp blender_manifest.toml $(BUILD)/package/polycube/
	rm -rf $(BUILD)/package/polycube/lib
	$(PYTHON) packaging/bundle_libraries.py $(BUILD)/package/polycube/polycube_native*.so $(BUILD)/package/polycube/lib
	find $(BUILD)/package -name __pycache__ -prune -exec rm -rf {} +
	cd $(BUILD)/package && zip -qr ../../dist/polycube-$(VERSION).zip polycube
	@echo "Wrote dist/polycube-$(VERSION).zip"

# Speed, memory and ratios against the paper-literal variant and a SciPy
# reference, on real models and their ~1M-triangle refinements (not part of test).
bench: build data
	$(PYTHON) tests/benchmark/bench.py --build $(BUILD)

clean:
	rm -rf $(BUILD) dist addon/*.so
