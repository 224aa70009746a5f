# Developer loop. `make demo` and `make test` are the README's quick start; .ci/run runs `make test`.
PYTHON ?= python3
VENV ?= .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed

.PHONY: demo test lint bench detector-bench clean

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e '.[test]'
	touch $(STAMP)

demo: $(STAMP)
	$(BIN)/cmtool demo --out out/demo

lint: $(STAMP)
	$(BIN)/ruff check .
	$(BIN)/lint-imports

# the numba kernels compiled first in two processes (from an empty cache: 1.5 minutes, then
# loaded), then two pytest-xdist workers (the CI machine has two cores), tests handed out as
# workers free up (worksteal). Python's bytecode caches are written even where the machine
# sets PYTHONDONTWRITEBYTECODE (an empty value unsets it): without them every process (each
# worker, each model-fit process, each `cmtool` subprocess of the tests) compiles the sources
# and pytest rewrites every test module again, 7 s of each worker's collection (stop 89).
test: lint
	PYTHONDONTWRITEBYTECODE= PYTHONPATH=. $(BIN)/python tests/kernel_warmer.py --processes 2
	PYTHONDONTWRITEBYTECODE= $(BIN)/python -m pytest -n 2 --dist worksteal

bench: $(STAMP)
	$(BIN)/python benchmarks/bench_model.py
	$(BIN)/python benchmarks/bench_features.py
	$(BIN)/python benchmarks/bench_generate.py
	$(BIN)/python benchmarks/bench_generate_rig.py
	$(BIN)/python benchmarks/bench_detectors.py
	$(BIN)/python benchmarks/bench_train.py
	$(BIN)/python benchmarks/bench_diagnose.py

# docs/benchmark.md: the detector benchmark (about 3 + 1.5 minutes on two cores)
detector-bench: $(STAMP)
	$(BIN)/cmtool generate datasets/detector-bench.toml --out out/detector-bench --workers 2 --resume
	$(BIN)/cmtool bench out/detector-bench --workers 2 --out out/detector-bench-results

clean:
	rm -rf $(VENV) out .pytest_cache
