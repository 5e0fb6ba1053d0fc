# archquake: the two commands a fresh machine needs.
#   make demo   create .venv, install archquake, compile its numerical kernels once (archquake
#               warm), reproduce Oppenheim's arch into out/ and assess the example bridge
#               (examples/bridge.toml, quick mode) into out/bridge/
#   make test   create .venv, install archquake with its test dependencies, run ruff, mypy
#               (0 errors) and the test suite (without the full-resolution studies marked slow,
#               each of which has a quick version in it; run those with
#               .venv/bin/python -m pytest -m slow)
PYTHON ?= python3.11
VENV   := .venv
BIN    := $(VENV)/bin
STAMP_RUN  := $(VENV)/.installed-run
STAMP_TEST := $(VENV)/.installed-test
UV := $(BIN)/uv pip install --quiet --python $(BIN)/python
# pytest-xdist workers for make test (one per core of the 2-core machines it is sized for)
TEST_WORKERS ?= 2
# archquake warm's workloads in two halves of about equal compile time, one process each (make demo
# and make test both warm this way)
WARM_A := events measures rigid
WARM_B := verdicts dem four-link domains ida

.PHONY: demo test bench lint clean

# uv installs the packages (pip itself only installs uv): it resolves and unpacks in a few seconds
# where pip took about twenty
$(BIN)/python:
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet uv

# the packages are byte-compiled by compileall, on every core
$(STAMP_RUN): pyproject.toml | $(BIN)/python
	$(UV) -e ".[records]"
	$(BIN)/python -m compileall -q -j 0 -x '/tests?/' $(VENV)/lib > /dev/null || true
	touch $@

$(STAMP_TEST): pyproject.toml | $(BIN)/python
	$(UV) -e ".[test]"
	$(BIN)/python -m compileall -q -j 0 -x '/tests?/' $(VENV)/lib > /dev/null || true
	touch $@ $(STAMP_RUN)

# archquake's own modules byte-compiled on every core before the commands start: where the
# environment sets PYTHONDONTWRITEBYTECODE (CI machines often do), every process would otherwise
# compile each module it imports from source (about 0.15 s a process; the test suite starts
# dozens); up to date, this takes a fraction of a second
PYC := $(BIN)/python -m compileall -q -j 0 src > /dev/null

demo: $(STAMP_RUN)
	@$(PYC)
	@# the kernels are compiled in two processes, one a core (the halves of about equal time)
	$(BIN)/archquake warm --only $(WARM_A) & warm=$$!; \
	$(BIN)/archquake warm --only $(WARM_B); warmed=$$?; wait $$warm && test $$warmed = 0
	$(BIN)/archquake demo --out out
	$(BIN)/archquake assess examples/bridge.toml --out out/bridge --quick
	@echo "the paper reproduced:   out/report.html"
	@echo "the bridge assessed:    out/bridge/report.html"

test: $(STAMP_TEST)
	@$(PYC)
	@command -v chromium >/dev/null 2>&1 || (apt-get update -qq >/dev/null && \
		DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium >/dev/null) || \
		echo "note: chromium could not be installed; the report's browser test will skip"
	$(BIN)/ruff check src tests benchmarks examples
	@# numba's kernels are compiled once, by archquake warm in two processes (their workloads
	@# balanced), before the test workers start: otherwise each worker compiles every kernel it
	@# calls. mypy runs beside the test workers, on the CPU time they leave idle (about a fifth:
	@# waits on subprocesses, clusters, the last files). The workers take whole files, the
	@# longest first (tests/conftest.py orders them)
	$(BIN)/archquake warm --only $(WARM_A) & warm=$$!; \
	$(BIN)/archquake warm --only $(WARM_B); warmed=$$?; wait $$warm || warmed=1; \
	$(BIN)/mypy src/archquake > .mypy.out 2>&1 & mypy=$$!; \
	$(BIN)/python -m pytest -q -n $(TEST_WORKERS) --dist loadfile --no-loadscope-reorder; tests=$$?; \
	wait $$mypy; typing=$$?; cat .mypy.out; rm -f .mypy.out; \
	test $$warmed = 0 && test $$tests = 0 && test $$typing = 0

bench: $(STAMP_RUN)
	$(BIN)/python benchmarks/run_all.py

lint: $(STAMP_TEST)
	$(BIN)/ruff check src tests benchmarks examples
	$(BIN)/mypy src/archquake

clean:
	rm -rf $(VENV) out .pytest_cache
