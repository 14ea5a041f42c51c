# wristkin: derive robot-wrist kinematics with SymPy and generate Python and C99 solvers.
#
# On a fresh machine (Debian: python3 with venv and pip, gcc, make):
#   make all     create .venv, install the project, regenerate generated/, run the demo
#   make test    the full test suite (what CI runs, through .ci/run)
#
# Every target that needs Python depends on the venv stamp, so each one works on its own.

SHELL := /bin/bash
.SHELLFLAGS := -eu -o pipefail -c
.DEFAULT_GOAL := all
# One step at a time even under `make -j`: `all` must regenerate before the demo runs.
.NOTPARALLEL:

PYTHON3 ?= python3
VENV ?= .venv
PY := $(VENV)/bin/python
STAMP := $(VENV)/.wristkin-installed
# gcc unless CC is given on the command line or in the environment (make's own default is cc).
ifeq ($(origin CC),default)
CC := gcc
endif
CSTRICT := -std=c99 -pedantic -Wall -Wextra -Werror
PYTEST_ARGS ?=
# Test workers (pytest-xdist): one per core.
TEST_WORKERS ?= auto
# The second pass of `make test-portable`: another CPU's numeric kernels and another set of random cases.
PORTABLE_SEED ?= 2
# Numerically sensitive tests: every comparison against the independent reference, the fuzz tests and the
# drift check. Own robots derived by an earlier pass of the checkout are reused (tests/derived_cache.py).
SENSITIVE_TESTS := tests/test_underactuated_wrist.py tests/test_reference_underactuated_wrist.py \
	tests/test_poly_real_roots.py tests/test_dh.py tests/test_reference_dh.py tests/test_screw_robots.py \
	tests/test_rsr_wrist.py tests/test_scara_rsr.py tests/test_reference_rsr_selfcheck.py \
	tests/test_casadi_functions.py tests/test_fuzz.py tests/test_fuzz_python.py tests/test_generated_fresh.py \
	tests/test_native.py tests/test_reproducers.py tests/test_chain_robots.py \
	tests/test_robot_descriptions.py tests/test_description_corpus.py tests/test_atlas.py tests/test_shared_runtime.py \
	tests/test_derived_robot.py \
	tests/test_general6r.py tests/test_general6r_solvers.py tests/test_runtime_eigen.py tests/test_uw_runtime.py \
	tests/test_serial_runtime.py tests/test_rsr_runtime.py tests/test_own_robots_near_singular.py

export PIP_DISABLE_PIP_VERSION_CHECK := 1
export PIP_NO_INPUT := 1
export MPLBACKEND := Agg

DEMO_POSE := -35.99 0.26 38.93
DEMO_JOINTS := 137.92 138.44 137.82

.PHONY: all setup venv native regenerate check-generated demo test test-portable test-haswell test-seeds fuzz lint bench clean distclean help

all: venv regenerate demo

setup: all

help:
	@echo "make all              venv + regenerate + demo (the README's first command)"
	@echo "make test             the full pytest suite, incl. drift check and C compile tests (WRISTKIN_TEST_SEED=N: other cases)"
	@echo "make test-portable    the numerically sensitive tests again as another CPU computes (Sandybridge kernels, no AVX2)"
	@echo "make test-haswell     the numerically sensitive tests as an AVX2 CPU without AVX-512 computes (HASWELL_SEED=N)"
	@echo "make test-seeds       test-portable and test-haswell under two seeds drawn now (printed)"
	@echo "make fuzz             1e6 fuzz cases per mechanism (1e7 in all) on the generated C under ASan/UBSan, then Python"
	@echo "make regenerate       rebuild generated/ from the derivations (and the C extension)"
	@echo "make native           compile the generated C into wristkin._native (Python then runs the C)"
	@echo "make check-generated  regenerate into a temp dir and diff against generated/"
	@echo "make demo             IK and FK of the paper's design on the command line"
	@echo "make lint             ruff on hand-written and generated Python; gcc $(CSTRICT) on generated C"
	@echo "make bench            benchmarks side by side with the peers (bench/run.py); rewrites README.md's measured block"
	@echo "make clean            remove caches and build outputs (keeps .venv)"
	@echo "make distclean        clean + remove .venv"

venv: $(STAMP)

# Re-install when the dependency pins change. A venv left half-made (no pip) is rebuilt.
# generated/python/wristkin must exist for the editable install (it is committed; mkdir
# only covers a checkout where it has not been generated yet).
$(STAMP): pyproject.toml setup.py
	@command -v $(PYTHON3) >/dev/null || { echo "error: $(PYTHON3) not found" >&2; exit 1; }
	@if ! $(PY) -m pip --version >/dev/null 2>&1; then \
		echo "creating $(VENV)"; rm -rf $(VENV); \
		$(PYTHON3) -m venv $(VENV) || { echo "error: '$(PYTHON3) -m venv' failed (Debian: apt-get install python3-venv)" >&2; exit 1; }; \
	fi
	mkdir -p generated/python/wristkin
	$(PY) -m pip install -e '.[dev]'
	touch $@

regenerate: $(STAMP)
	@TIMEFORMAT='regenerate: wall time %1R s'; time $(PY) -m derive.cli regenerate
	$(PY) -m derive.cli native

# The generated C compiled as wristkin._native beside the modules (pip install does the same); without it the
# modules run on numpy (wristkin.M.BACKEND).
native: $(STAMP)
	$(PY) -m derive.cli native

check-generated: $(STAMP)
	$(PY) -m derive.cli check

demo: $(STAMP)
	$(VENV)/bin/wristkin ik underactuated_wrist --pose $(DEMO_POSE)
	$(VENV)/bin/wristkin fk underactuated_wrist --joints $(DEMO_JOINTS)

# pytest exit code 5 means no tests were collected: that is a failure, not a pass.
test: $(STAMP)
	@rc=0; $(PY) -m pytest -n $(TEST_WORKERS) --dist worksteal --durations=15 $(PYTEST_ARGS) || rc=$$?; \
	if [ $$rc -eq 5 ]; then echo "error: pytest collected no tests (exit code 5)" >&2; fi; \
	exit $$rc

# The repeated passes skip the tests marked c_only (C programs under the sanitizers and the fuzzer, compared with
# nothing numpy computes, so no BLAS kernel or numpy loop reaches them): `make test` runs them once per CI run, and
# `make test-seeds` on its drawn seeds too (SENSITIVE_SELECT= runs everything).
SENSITIVE_SELECT ?= -m "not c_only"

# As a CPU without AVX2 computes: OpenBLAS's Sandybridge kernels, numpy's AVX2/FMA3 loops off, other cases, and
# the numpy fallback instead of the C extension (the first pass runs the C wherever it is built).
test-portable: $(STAMP)
	@rc=0; OPENBLAS_CORETYPE=Sandybridge NPY_DISABLE_CPU_FEATURES=X86_V3 WRISTKIN_TEST_SEED=$(PORTABLE_SEED) \
	WRISTKIN_BACKEND=numpy \
	$(PY) -m pytest -n $(TEST_WORKERS) --dist worksteal $(SENSITIVE_SELECT) $(SENSITIVE_TESTS) $(PYTEST_ARGS) || rc=$$?; \
	if [ $$rc -eq 5 ]; then echo "error: pytest collected no tests (exit code 5)" >&2; fi; \
	exit $$rc

# As the AVX2 CPU without AVX-512 that CI may run on computes (OpenBLAS Haswell kernels, numpy's AVX-512 loops
# off), with the C extension, on another set of random cases (HASWELL_SEED; CI draws it per run and prints it).
HASWELL_SEED ?= 3
test-haswell: $(STAMP)
	@rc=0; OPENBLAS_CORETYPE=Haswell NPY_DISABLE_CPU_FEATURES="X86_V4 AVX512_ICL AVX512_SPR" \
	WRISTKIN_TEST_SEED=$(HASWELL_SEED) \
	$(PY) -m pytest -n $(TEST_WORKERS) --dist worksteal $(SENSITIVE_SELECT) $(SENSITIVE_TESTS) $(PYTEST_ARGS) || rc=$$?; \
	if [ $$rc -eq 5 ]; then echo "error: pytest collected no tests (exit code 5)" >&2; fi; \
	exit $$rc

# The sensitive tests under two seeds drawn now and printed (make test-portable and make test-haswell with them):
# "every seed must pass", tried on cases no run saw before.
test-seeds: $(STAMP)
	@a=$$(( (RANDOM << 15 | RANDOM) % 1000000 + 1 )); b=$$(( (RANDOM << 15 | RANDOM) % 1000000 + 1 )); \
	echo "== test seeds drawn: $$a (portable), $$b (haswell)"; rc=0; \
	$(MAKE) --no-print-directory test-portable PORTABLE_SEED=$$a SENSITIVE_SELECT= || rc=$$?; \
	$(MAKE) --no-print-directory test-haswell HASWELL_SEED=$$b SENSITIVE_SELECT= || rc=$$?; \
	[ $$rc -eq 0 ] || echo "failed with test seeds $$a (portable), $$b (haswell)" >&2; exit $$rc

# 1e6 cases per mechanism through the C fuzz driver (10 mechanisms: 1e7), then 20x the Python examples.
FUZZ_CASES ?= 1000000
fuzz: $(STAMP)
	WRISTKIN_FUZZ_CASES=$(FUZZ_CASES) WRISTKIN_FUZZ_EXAMPLES=3000 $(PY) -m pytest -n $(TEST_WORKERS) -rP \
	tests/test_fuzz.py tests/test_fuzz_python.py $(PYTEST_ARGS)

# All three checks run; the target fails if any of them failed.
lint: $(STAMP)
	@rc=0; \
	echo "ruff check $(wildcard derive tests bench atlas runtime)"; \
	$(PY) -m ruff check $(wildcard derive tests bench atlas runtime) || rc=1; \
	echo "ruff check generated/python"; $(PY) -m ruff check generated/python || rc=1; \
	for f in runtime/c/wristkin_runtime.c tests/c/poly_roots_harness.c; do \
		echo "$(CC) $(CSTRICT) -Iruntime/c -c $$f"; \
		$(CC) $(CSTRICT) -Iruntime/c -c "$$f" -o /dev/null || rc=1; \
	done; \
	csrc="$(wildcard generated/c/*.c)"; \
	if [ -z "$$csrc" ]; then echo "error: no generated/c/*.c: run make regenerate" >&2; rc=1; fi; \
	for f in $$csrc; do \
		echo "$(CC) $(CSTRICT) -Igenerated/c -c $$f"; \
		$(CC) $(CSTRICT) -Igenerated/c -c "$$f" -o /dev/null || rc=1; \
	done; \
	exit $$rc

bench: $(STAMP)
	$(PY) -m pip install -q -e '.[dev,bench]'
	$(PY) bench/run.py --regenerate --readme

clean:
	rm -rf build .pytest_cache .ruff_cache .mypy_cache .hypothesis *.egg-info
	find . -path ./$(VENV) -prune -o -name __pycache__ -type d -exec rm -rf {} +

distclean: clean
	rm -rf $(VENV)
