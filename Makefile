# odgen: `make demo` and `make test` work on a fresh machine; each sets up .venv first.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed

.PHONY: setup sysdeps demo test corpus lint-code docs release bench fuzz clean

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install -q --upgrade pip
	$(BIN)/python -m pip install -q -e '.[test]'
	touch $@

setup: $(STAMP)

# The main job on the example: lint it, generate its C dictionary, compile it with the
# runtime and run the self-test (which reports where each storage class landed and its
# size), then write the lint findings as SARIF and convert the description back to EDS.
# Needs Python and a C compiler only (`odgen check` names CC when there is none).
demo: setup
	$(BIN)/odgen lint examples/*/*.eds
	mkdir -p build/demo
	$(BIN)/odgen generate examples/io-node/io-node.eds --options examples/io-node/io-node.toml -o build/demo
	$(BIN)/odgen check examples/io-node/io-node.eds --options examples/io-node/io-node.toml --keep build/demo/check
	$(BIN)/odgen lint --format sarif -o build/demo/examples.sarif examples/*/*.eds
	$(BIN)/odgen convert examples/io-node/io-node.eds build/demo/io-node.eds
	@echo "demo: C dictionary in build/demo/io_node.[ch], SARIF in build/demo/examples.sarif"

lint-code: setup
	$(BIN)/ruff check odgen tests benchmarks examples $(wildcard fuzz)
	$(BIN)/mypy

# System tools the tests compile, build, emulate and render reports with, as CHECK:PACKAGE (a
# Debian package, installed when CHECK, a command or a file it provides, is missing). The cross
# compilers, C libraries and emulators run the self-test on other cores (tests/test_target_cores.py).
SYSTOOLS := gcc:gcc clang:clang cmake:cmake chromium:chromium \
	arm-none-eabi-gcc:gcc-arm-none-eabi /usr/lib/arm-none-eabi/newlib:libnewlib-arm-none-eabi \
	qemu-system-arm:qemu-system-arm qemu-ppc:qemu-user \
	powerpc-linux-gnu-gcc:gcc-powerpc-linux-gnu /usr/powerpc-linux-gnu/lib/libc.a:libc6-dev-powerpc-cross \
	avr-gcc:gcc-avr /usr/lib/avr/include/avr/io.h:avr-libc simavr:simavr
sysdeps:
	@missing=""; for t in $(SYSTOOLS); do check=$${t%%:*}; \
	  case $$check in /*) test -e $$check ;; *) command -v $$check >/dev/null 2>&1 ;; esac || missing="$$missing $${t#*:}"; \
	done; \
	if [ -n "$$missing" ]; then apt-get update -qq && apt-get install -y -qq $$missing; fi

# The CAN tests set up tools/vcan themselves (host vcan, else a User-Mode Linux guest).
# tests/test_install.py installs the wheel under the oldest Python pyproject.toml declares
# (tools/oldest-python.sh finds it, or installs it from the package sources).
# The suite runs on every core (pytest-xdist; what tests share stays on one worker: tests/README.md).
TEST_WORKERS ?= auto
PYTEST := $(BIN)/python -m pytest -q -n $(TEST_WORKERS) --dist loadgroup
test: setup lint-code sysdeps
	oldest=$$(tools/oldest-python.sh) && ODGEN_OLDEST_PYTHON=$$oldest $(PYTEST)

# The tests that take a sample of the corpus in `make test` (CORPUS_SAMPLE in tests/conftest.py),
# on every corpus file: a node program of each on the CAN bus (round trip, conformance battery).
CORPUS_TESTS := tests/test_roundtrip_vcan.py tests/test_conformance.py
corpus: setup sysdeps
	ODGEN_CORPUS=all $(PYTEST) $(CORPUS_TESTS)

# docs/rules.md is generated from the rule catalogue (a test checks it is current).
docs: setup
	$(BIN)/odgen rules --markdown > docs/rules.md

# What .github/workflows/release.yml does on a tag (docs/releasing.md): sdist and wheel into
# dist/, twine check, then the wheel alone in a fresh venv outside the checkout, smoke-tested.
release: setup
	rm -rf dist
	$(BIN)/python -m build --outdir dist .
	$(BIN)/twine check --strict dist/*
	tools/release-smoke.sh dist build/release-venv

bench:
	@set -e; t0=$$(date +%s); $(MAKE) --no-print-directory setup sysdeps; \
	command -v arm-none-eabi-gcc >/dev/null && command -v valgrind >/dev/null || \
	  { apt-get update -qq && apt-get install -y -qq gcc-arm-none-eabi valgrind; }; \
	test -f build/bench-venv/.installed || { $(PYTHON) -m venv build/bench-venv && \
	  build/bench-venv/bin/python -m pip install -q objdictgen==3.5.5 canopen==2.4.1 && \
	  touch build/bench-venv/.installed; }; \
	nice -n 10 $(BIN)/python benchmarks/run.py --started $$t0

# bench: peers in their own venv (build/bench-venv), Cortex-M4 compiler and valgrind from apt;
# results in benchmarks/results/latest.md (benchmarks/README.md); the master's boot time runs on
# vcan (one short User-Mode Linux guest when the host has no vcan). bench-sdo: SDO speed over
# vcan (boots a User-Mode Linux guest when the host has no vcan).
bench-sdo: setup
	bash tools/vcan/setup.sh
	$(BIN)/python tools/vcan/run.py -- $(BIN)/python benchmarks/sdo_speed.py

# Fuzzing budgets (docs/robustness.md, which the last step regenerates): parser inputs,
# runtime executions per libFuzzer harness, random firmware sequences through the persistence
# layer (tests/persist_model.py). Findings fail the target.
FUZZ_INPUTS ?= 1000000
FUZZ_RUNS   ?= 10000000
FUZZ_PERSIST_SEQUENCES ?= 20000
fuzz: setup sysdeps
	$(BIN)/python fuzz/parsers.py --inputs $(FUZZ_INPUTS)
	nice -n 5 $(BIN)/python fuzz/persist_sequences.py --sequences $(FUZZ_PERSIST_SEQUENCES)
	bash fuzz/runtime/run.sh $(FUZZ_RUNS)
	$(BIN)/python fuzz/report.py

clean:
	rm -rf build .pytest_cache
