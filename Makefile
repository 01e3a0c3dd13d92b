# Quick start on a fresh Debian machine (as root, or with sudo):
#   make demo   installs what is missing, builds in Release what the demo runs (not the tests), runs both paper
#               examples into out/ and lists their figures
#   make test   the same set-up, then the whole test suite (Release, an install to a scratch prefix with a
#               consumer project and the build tree moved away, pip and wheel installs with the Python tests
#               against them (pip packages build/ci's module and command, the wheel is compiled from the
#               sdist), then ASan + UBSan on all but the slow numerical verifications (ctest -LE verification:
#               the quick suite and the slow tests of the parsers, outputs and command line), then a bounded
#               fuzzing run)
#   make fuzz   only the fuzzing run: the input layer's libFuzzer targets (clang), FUZZ_SECONDS each
PACKAGES := cmake g++ make libtomlplusplus-dev libmuparser-dev libcli11-dev libfmt-dev \
            nlohmann-json3-dev libkissfft-dev libgtest-dev libbenchmark-dev \
            python3 python3-dev pybind11-dev python3-numpy python3-matplotlib python3-pytest \
            libopenmpi-dev openmpi-bin python3-scipy \
            clang-14 libclang-rt-14-dev python3-hypothesis \
            python3-venv python3-pip python3-setuptools python3-wheel python3-build python3-pandas python3-mypy \
            libhdf5-dev python3-h5py libceres-dev
PYTHON := /usr/bin/python3
JOBS ?= $(shell nproc)
EXAMPLES := paper-example1 paper-example2
FUZZ_TARGETS := case overrides sweep
FUZZ_SECONDS ?= 55

.PHONY: deps build demo test fuzz bench verification format clean

deps:
	@missing=""; for p in $(PACKAGES); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "install ok installed" || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  echo "Installing Debian packages:$$missing"; \
	  if [ "$$(id -u)" -ne 0 ]; then sudo=sudo; else sudo=; fi; \
	  $$sudo apt-get update -qq && \
	  DEBIAN_FRONTEND=noninteractive $$sudo apt-get install -y -qq --no-install-recommends $$missing; \
	fi

build: deps
	cmake --preset release
	cmake --build --preset release -j $(JOBS)

# The demo builds only what it runs (the command, the Python module that
# draws, results.h5's module), not the tests and benchmarks: `make test` does.
DEMO_TARGETS := barimpact_cli barimpact_python barimpact_hdf5_module

demo: deps
	cmake --preset release
	cmake --build --preset release -j $(JOBS) --target $(DEMO_TARGETS)
	@mkdir -p out
	@for ex in $(EXAMPLES); do \
	  echo "== $$ex"; \
	  ./build/release/barimpact run examples/$$ex.toml --out out/$$ex || exit $$?; \
	  ./build/release/barimpact plot out/$$ex > /dev/null || exit $$?; \
	  echo "  figures in out/$$ex/figures:" $$(cd out/$$ex/figures && ls *.png); \
	done

test: deps
	cmake --preset ci
	cmake --build --preset ci -j $(JOBS)
	ctest --preset ci -j $(JOBS)
	bash tests/install/install_test.sh build/ci
	bash tests/install/pip_test.sh build/ci
	cmake --preset dev
	cmake --build --preset dev -j $(JOBS)
	ctest --preset dev -j $(JOBS) -LE verification
	$(MAKE) --no-print-directory fuzz

fuzz: deps
	cmake --preset fuzz
	cmake --build --preset fuzz -j $(JOBS)
	bash tests/fuzz/run.sh build/fuzz $(FUZZ_SECONDS) $(FUZZ_TARGETS)

bench: build
	$(PYTHON) bench/report.py build/release/bench/barimpact_bench docs/benchmarks.md

verification: build
	bash docs/verification.sh build/release/barimpact

format:
	clang-format -i $$(git ls-files '*.cpp' '*.hpp')

clean:
	rm -rf build out
