# Tessella - the two commands a newcomer needs: `make demo` and `make test`.
SHELL := /bin/bash
PY := /usr/bin/python3
FREECAD_LIB := /usr/lib/freecad-python3/lib
BUILD := build
JOBS ?= 2

# Debian bookworm packages, exactly what the build, the tests and the demo use.
DEB_PACKAGES := g++ make cmake freecad freecad-python3 \
  libocct-foundation-dev libocct-modeling-data-dev libocct-modeling-algorithms-dev \
  libpolyclipping-dev libtbb-dev libeigen3-dev pybind11-dev python3-dev \
  libgtest-dev libbenchmark-dev \
  python3-numpy python3-matplotlib python3-ezdxf python3-pytest xvfb xauth

# Only for `make bench` (the Gmsh comparison; SciPy's MILP solver checks the
# families' cover against the optimum), never for the build or the tests.
BENCH_PACKAGES := python3-gmsh python3-scipy occt-misc

.PHONY: all deps bench-deps build test test-cpp test-python test-gui sanitize demo bench screenshots install uninstall format clean

all: build

deps bench-deps: PACKAGES = $(DEB_PACKAGES)
bench-deps: PACKAGES = $(BENCH_PACKAGES)
deps bench-deps:
	@missing=""; for p in $(PACKAGES); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "install ok installed" || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  echo "Installing missing Debian packages:$$missing"; \
	  SUDO=""; [ "$$(id -u)" = 0 ] || SUDO=sudo; \
	  $$SUDO apt-get update && DEBIAN_FRONTEND=noninteractive $$SUDO apt-get install -y --no-install-recommends $$missing; \
	else echo "All Debian packages present."; fi

$(BUILD)/Makefile: CMakeLists.txt
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release

build: deps $(BUILD)/Makefile
	cmake --build $(BUILD) -j$(JOBS)

# All tests: C++ (gtest), Python under headless FreeCAD (pytest), GUI under Xvfb.
# Ends with one summary line "N passed, M failed".
test: build
	$(PY) tests/run_all.py

test-cpp: build
	$(BUILD)/tessella_tests

test-python: build
	PYTHONPATH=$(FREECAD_LIB):$(CURDIR) $(PY) -m pytest -q tests/python

test-gui: build
	$(PY) tests/run_all.py --only gui

# The C++ tests, the fingerprint cases and the face-set / boundary_driven
# Python tests under ASan + UBSan + libstdc++ assertions, built apart in
# build-sanitize/ (about 25 minutes; SANITIZE_PYTEST=all for every Python test;
# SANITIZE_KIND=thread for ThreadSanitizer in build-sanitize-thread/).
sanitize: deps
	bash tests/sanitize.sh

demo: build
	PYTHONPATH=$(FREECAD_LIB):$(CURDIR) $(PY) examples/demo.py --out out
	PYTHONPATH=$(FREECAD_LIB):$(CURDIR) $(PY) examples/fabrication_demo.py --out out/fabrication

# Speed: google-benchmark, preview latency, no cliff on a big surface,
# Tessella vs Gmsh vs MeshPart, and the scaling to 128k panels.
bench: build bench-deps
	$(BUILD)/tessella_bench
	PYTHONPATH=$(FREECAD_LIB):$(CURDIR) $(PY) bench/preview_latency.py
	PYTHONPATH=$(FREECAD_LIB):$(CURDIR) $(PY) bench/document_speed.py
	PYTHONPATH=$(FREECAD_LIB):$(CURDIR) $(PY) bench/no_cliff.py
	PYTHONPATH=$(FREECAD_LIB):$(CURDIR) $(PY) bench/gmsh_compare.py
	PYTHONPATH=$(FREECAD_LIB):$(CURDIR) $(PY) bench/scaling.py

# README pictures of the workbench (toolbar, task panel, preview, colours).
screenshots: build
	QTWEBENGINE_DISABLE_SANDBOX=1 TESSELLA_ROOT=$(CURDIR) xvfb-run -a -s "-screen 0 1600x1000x24" freecad tests/gui/make_screenshots.py

# Link the repository into FreeCAD's user Mod folder (FreeCAD 0.20 path).
MOD_DIR := $(HOME)/.local/share/FreeCAD/Mod
install: build
	mkdir -p $(MOD_DIR)
	ln -sfn $(CURDIR) $(MOD_DIR)/Tessella
	@echo "Linked $(CURDIR) -> $(MOD_DIR)/Tessella; restart FreeCAD and pick the Tessella workbench."

uninstall:
	rm -f $(MOD_DIR)/Tessella

format:
	clang-format -i $$(git ls-files 'cpp_core/*.h' 'cpp_core/*.cpp' 'bindings/*.cpp' 'bindings/*.h' 'tests/cpp/*' 'bench/*.cpp')

clean:
	rm -rf $(BUILD) freecad_workbench/_core*.so out
