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
# and make test both warm this way). The event integrator alone is half of it; it compiles the
# contact projection and the joint forces' probe first, which the second half's last two
# workloads then load from the cache rather than compile a second time
WARM_A := events
WARM_B := four-link domains ida dem measures verdicts rigid

.PHONY: demo test bench lint clean

# uv installs the packages (pip itself only installs uv): it resolves and unpacks in a few seconds
# where pip took about twenty
$(BIN)/python:
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet uv

$(STAMP_RUN): pyproject.toml | $(BIN)/python
	$(UV) -e ".[records]"
	touch $@

$(STAMP_TEST): pyproject.toml | $(BIN)/python
	$(UV) -e ".[test]"
	touch $@ $(STAMP_RUN)

# Python writes each module's bytecode the first time a command imports it, and every later
# process reads it. Where the environment sets PYTHONDONTWRITEBYTECODE (CI machines often do),
# each process would compile from source every module it imports (numpy, scipy, numba and
# archquake: about 2 s a process; the test suite starts dozens). Byte-compiling the whole
# environment ahead (10,000 modules) took 10 s on 2 cores; the 2,800 the commands import take
# 6 s of CPU, once, as they are first imported
unexport PYTHONDONTWRITEBYTECODE

demo: $(STAMP_RUN)
	@# the kernels are compiled in two processes, one a core (the halves of about equal time)
	$(BIN)/archquake warm --only $(WARM_A) & warm=$$!; \
	$(BIN)/archquake warm --only $(WARM_B); warmed=$$?; wait $$warm && test $$warmed = 0
	$(BIN)/archquake demo --out out
	$(BIN)/archquake assess examples/bridge.toml --out out/bridge --quick
	@echo "the paper reproduced:   out/report.html"
	@echo "the bridge assessed:    out/bridge/report.html"

test: $(STAMP_TEST)
	@command -v chromium >/dev/null 2>&1 || (apt-get update -qq >/dev/null && \
		DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium >/dev/null) || \
		echo "note: chromium could not be installed; the report's browser test will skip"
	$(BIN)/ruff check src tests benchmarks examples
	@# numba's kernels are compiled once, by archquake warm in two processes (their workloads
	@# balanced), before the test workers start: otherwise each worker compiles every kernel it
	@# calls. mypy starts on the core the shorter half leaves and goes on beside the test
	@# workers (they keep about four fifths of the two cores busy: waits on subprocesses and
	@# clusters, the last files; a third worker was no faster). The workers take whole files,
	@# the longest first (tests/conftest.py orders them)
	$(BIN)/archquake warm --only $(WARM_A) & warm=$$!; \
	$(BIN)/archquake warm --only $(WARM_B); warmed=$$?; \
	$(BIN)/mypy src/archquake > .mypy.out 2>&1 & mypy=$$!; \
	wait $$warm || warmed=1; \
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
