# One command builds the book (`make book`), one tests it (`make test`).
# Everything runs inside .venv, created from environment.lock (hash-pinned, Python 3.11.7).
SHELL := /bin/bash
.SHELLFLAGS := -eu -o pipefail -c
.DEFAULT_GOAL := help

PYTHON_BOOT ?= python3
VENV        := .venv
PY          := $(VENV)/bin/python
UV          := $(VENV)/bin/uv
STAMP       := $(VENV)/.lock-stamp
# PROFILE selects the notebooks' parameters: "ci" (their defaults, what `make test` runs and
# tests/references records) or a folder notebooks/profiles/<name>/ of papermill YAML files, one
# per notebook that differs (e.g. `make book PROFILE=full`); each profile builds in its own folder.
PROFILE     ?= ci
BUILD       := build$(if $(filter-out ci,$(PROFILE)),/$(PROFILE))
PROFILE_DIR := notebooks/profiles/$(PROFILE)
RERUN       := $(BUILD)/rerun
# the chapters in execution order, and which chapter's record gives another its inputs: declared
# once, in mechlib/pipeline/chapters.py (it runs on the standard library alone)
CHAPTERS    := mechlib/pipeline/chapters.py
NB_NAMES    := $(shell $(PYTHON_BOOT) $(CHAPTERS) order)
NB_EDGES    := $(shell $(PYTHON_BOOT) $(CHAPTERS) edges)
NB_DEFERRED := $(shell $(PYTHON_BOOT) $(CHAPTERS) deferred)
# what the notebooks import: the science wing, mechlib minus the build wing (mechlib/pipeline/),
# so a change in the build wing rebuilds the book without re-executing the notebooks
MECHLIB_SRC := $(filter-out mechlib/pipeline/%,$(shell find mechlib -name '*.py' 2>/dev/null))
EXECUTED    := $(patsubst %,$(BUILD)/executed/%.ipynb,$(NB_NAMES))
PIPELINE    := $(PY) -m mechlib.pipeline
# the FE results store (store/) and the stamp of the build's FE cache seeded from it: every target
# that executes a notebook (book, run, notebooks, test, store) reads the store's runs instead of
# solving them; a stale, edited or corrupt store is refused in one line before any notebook runs
STORE       := store
# the notebooks' FE cache (mechlib.paths.fe_cache_dir: every profile reads the same one)
FE_CACHE    := build/cache/experiments
STORE_SEEDED := $(FE_CACHE)/.store-seeded
# the targets that compare with tests/references run the ci profile only
REQUIRE_CI   = @test "$(PROFILE)" = ci || { echo "make $@ runs the ci profile (tests/references); got PROFILE=$(PROFILE)"; exit 2; }
export PYTHONHASHSEED := 0
export PYDEVD_DISABLE_FILE_VALIDATION := 1
# .venv is a build product: let Python cache its bytecode there. With PYTHONDONTWRITEBYTECODE set
# (as on some CI machines) every process — each notebook kernel, pytest, the book build —
# compiles SfePy, SymPy, SciPy … again: measured 7.0 s against 2.9 s to import the FE stack.
unexport PYTHONDONTWRITEBYTECODE

.PHONY: help env book test test-first test-rerun test-book test-side store-check-reuse unit unit-a unit-b notebooks rerun check-records check-book check-browser run references lint \
        bench lock clean store store-seed store-check book-checks determinism-check

help:
	@echo "make book        build the HTML book (creates .venv from environment.lock, executes notebooks,"
	@echo "                 one per core in the order of their inputs; BOOK_JOBS=1: one at a time)"
	@echo "                 PROFILE=full: notebooks/profiles/full/ (a finer mesh-convergence study of the linear model)"
	@echo "make test        unit tests + every notebook + reference comparison + book build and checks"
	@echo "make check-browser  open every built page in headless Chromium, network off (needs chromium)"
	@echo "make rerun       execute every notebook again, cold, into build/rerun (make test compares records)"
	@echo "                 FE_CACHE_FROM=build/cache/experiments: FE results from a copy of that cache"
	@echo "                 FIRST_RUN=build: chapters' inputs from the first run's records, longest first"
	@echo "make run NB=name ARGS='-p key value ...'   re-run one notebook with new parameters"
	@echo "make references  re-record tests/references/ from a fresh run and show what changed"
	@echo "make bench       speed benchmarks (ratios measured in one run); ONLY=nonlinear,chapter: some"
	@echo "                 ONLY=book: make book on a fresh clone of HEAD, its time and each chapter's"
	@echo "make pdf         print the built book to book/_build/pdf/book.pdf (headless Chromium; after make book)"
	@echo "make check-pdf   check that PDF: page count, page titles, every figure, no raw TeX"
	@echo "make lock        regenerate environment.lock from requirements.in"
	@echo "make store       regenerate the FE results store (store/) from the notebooks' FE runs;"
	@echo "                 resumes from build/cache; FROM_EMPTY=1: from an empty cache;"
	@echo "                 DASK_SCHEDULER=tcp://host:port: the runs on that Dask cluster"

# --- environment ------------------------------------------------------------------------------
env: $(STAMP)

$(UV): .ci/bootstrap.lock
	test -x $(PY) || $(PYTHON_BOOT) -m venv $(VENV)
	$(PY) -m pip install -q --disable-pip-version-check --require-hashes -r .ci/bootstrap.lock
	touch $@

$(STAMP): environment.lock $(UV) pyproject.toml
	$(UV) pip sync -q --python $(PY) environment.lock
	$(UV) pip install -q --python $(PY) --no-deps --no-build-isolation -e .
	touch $@

lock: $(UV)
	$(UV) pip compile requirements.in --generate-hashes --python-version 3.11.7 -o environment.lock

# --- notebooks --------------------------------------------------------------------------------
# An executed notebook depends on its source, on mechlib and on the environment: nothing else
# changes its output, so an unchanged notebook is not re-executed.
$(BUILD)/executed/%.ipynb: notebooks/%.ipynb $(MECHLIB_SRC) $(STAMP) $(wildcard $(PROFILE_DIR)/*.yaml) \
  | $(STORE_SEEDED)
	@test "$(PROFILE)" = ci || test -d $(PROFILE_DIR) || { echo "no profile $(PROFILE_DIR)"; exit 2; }
	@mkdir -p $(BUILD)/executed $(BUILD)/records
	@echo "executing $< (profile $(PROFILE))"
	@# into a temporary name that papermill accepts without a warning (it wants .ipynb or .json)
	$(PIPELINE) execute --notebook $< --out $(BUILD)/executed/$*.tmp.ipynb --records $(BUILD)/records \
	  -- $(if $(wildcard $(PROFILE_DIR)/$*.yaml),-f $(PROFILE_DIR)/$*.yaml)
	mv $(BUILD)/executed/$*.tmp.ipynb $@

# a chapter executes after those whose records fill its inputs (the DOE chapter runs on the
# geometry and mesh that the HexFlex model chapter identifies)
$(foreach e,$(NB_EDGES),$(eval $(BUILD)/executed/$(word 1,$(subst :, ,$(e))).ipynb: \
  $(BUILD)/executed/$(word 2,$(subst :, ,$(e))).ipynb))

# scheduling only (chapters.DEFERRED): make starts the ready notebook that comes first in its
# list, so the quick chapters that feed no other wait (order-only) for the DOE chapter, and the
# longest chain, the model page → the DOE chapter → the meta-model page, goes first
$(foreach e,$(NB_DEFERRED),$(eval $(BUILD)/executed/$(word 1,$(subst :, ,$(e))).ipynb: | \
  $(BUILD)/executed/$(word 2,$(subst :, ,$(e))).ipynb))

notebooks: $(EXECUTED)

# The chapters run in parallel, each after those whose records fill its inputs (the graph above,
# as in make test): a plain `make book` starts a sub-make with BOOK_JOBS job slots, one per core
# (at most 4: each chapter's kernel holds its own FE models; BOOK_JOBS=1 runs them one at a
# time). The HTML is rebuilt from scratch (seconds): an incremental Sphinx build re-reports no
# warning of an unchanged page and skips copying book/_static when no page changed.
BOOK_JOBS   ?= $(shell n=$$(nproc 2>/dev/null || echo 1); echo $$(( n < 4 ? n : 4 )))
book: $(STAMP)
	$(MAKE) --no-print-directory -j$(BOOK_JOBS) notebooks
	$(PIPELINE) book --executed $(BUILD)/executed --records $(BUILD)/records --book book --profile $(PROFILE)
	rm -rf book/_build
	$(VENV)/bin/jupyter-book build book -W -n --keep-going --quiet
	@echo "Book: $(abspath book/_build/html/index.html)"

# --- tests ------------------------------------------------------------------------------------
# the unit tests in two processes, every other test file each (each its own temporary folder):
# in make test they share the cores with the store's cold sample, and the last of the three no
# longer leaves a core idle alone
UNIT_TESTS := $(filter-out tests/test_records.py tests/test_book_html.py tests/test_explorer_browser.py,\
  $(sort $(wildcard tests/test_*.py)))
unit: unit-a unit-b

unit-a unit-b: unit-%: $(STAMP)
	$(VENV)/bin/pytest -q -p no:cacheprovider --basetemp=$(BUILD)/pytest-$* \
	  $(shell printf '%s\n' $(UNIT_TESTS) | awk 'NR % 2 == $(if $(filter a,$*),1,0)')

check-records: $(EXECUTED)
	$(VENV)/bin/pytest -q tests/test_records.py

# the built HTML: no network requests, no machine paths or warnings, links resolve (after `make book`)
check-book: $(STAMP)
	MECHLIB_REQUIRE_BOOK=1 $(VENV)/bin/pytest -q tests/test_book_html.py tests/test_explorer_browser.py

# every built page in headless Chromium from file:// with the network off: math typeset, images
# loaded, glued numbers present (after `make book`)
check-browser: $(STAMP)
	$(PIPELINE) check-browser --html book/_build/html --book book

test: $(STAMP)
	$(REQUIRE_CI)
	$(VENV)/bin/ruff check mechlib tests notebooks
	$(VENV)/bin/ruff format --check mechlib tests notebooks
	@# The FE results store seeds the cache first. Then the work shares the two cores as a graph:
	@# the chapters' chain (every notebook, their records against the references, the determinism
	@# re-run of every notebook from a copy of the first run's cache, the records compared), the
	@# book, its checks and the PDF once the first run's notebooks are done and their records
	@# checked, and beside them, at a lower priority, the work nothing waits on: the unit tests and
	@# the store's cold sample, from the start. The chain is the longest path; the low-priority
	@# work fills the cores it leaves idle (two chapters waiting on one, the last chapters' tail).
	@# (The book's checks keep the normal priority: the browser's pages have timeouts.)
	@# The notebooks run with a BLAS kernel other than this machine's own and the references'
	@# (OPENBLAS_CORETYPE; mechlib/pipeline/kernels.py): their records are compared with the
	@# references across kernels, and with the re-run's byte for byte on one kernel.
	$(MAKE) --no-print-directory $(STORE_SEEDED)
	kernel=$$($(KERNELS) other tests/references); \
	echo "make test: the notebooks run with OpenBLAS's $$kernel kernel (this machine's: $$($(KERNELS) own))"; \
	$(MAKE) --no-print-directory -j4 test-rerun test-book test-side TEST_KERNEL=$$kernel

# the BLAS kernel of make test's notebooks (set by `make test`; empty: the machine's own)
KERNELS     := $(PY) -m mechlib.pipeline.kernels
WITH_KERNEL  = $(if $(TEST_KERNEL),OPENBLAS_CORETYPE=$(TEST_KERNEL))

# Work at a low priority. `nice` alone does not rank it below the notebooks where the kernel
# groups processes by session for scheduling (Linux's autogroups, on by default): each notebook's
# kernel starts a session of its own, and the kernel shares the cores fairly between sessions,
# whatever their processes' nice values. So the work starts a session of its own (`setsid`) and
# lowers that session's priority too (/proc/self/autogroup), where the machine has autogroups.
LOW_PRIORITY = setsid --wait sh -c 'if test -w /proc/self/autogroup; then echo 5 > /proc/self/autogroup; fi; exec nice -n 5 "$$@"' low

# the steps of `make test` (each a sub-make with its own job slots)
test-first: $(STAMP)
	$(if $(TEST_KERNEL),$(KERNELS) forget $(BUILD)/records $(BUILD)/executed $(TEST_KERNEL))
	$(WITH_KERNEL) $(MAKE) --no-print-directory -j2 notebooks
	$(if $(TEST_KERNEL),MECHLIB_TEST_KERNEL=$(TEST_KERNEL)) $(MAKE) --no-print-directory check-records

test-rerun: test-first
	$(WITH_KERNEL) $(MAKE) --no-print-directory rerun FE_CACHE_FROM=$(BUILD)/cache/experiments FIRST_RUN=$(BUILD)
	$(MAKE) --no-print-directory determinism-check \
	  $(if $(wildcard $(STORE)/manifest.json),DETERMINISM_ARGS='--store-checked $(STORE)')

test-book: test-first
	$(MAKE) --no-print-directory book-checks

# the unit tests (temporary folders only) and the store's cold sample, in which glibc keeps
# freed memory for reuse (its model builds otherwise spend a third of their time in the kernel,
# mapping and unmapping large arrays: measured 82 s of system time against 49 s)
test-side: $(STAMP)
	$(LOW_PRIORITY) $(MAKE) --no-print-directory -j3 unit-a unit-b store-check-reuse

store-check-reuse: $(STAMP)
	MALLOC_MMAP_MAX_=0 MALLOC_TRIM_THRESHOLD_=17179869184 $(MAKE) --no-print-directory store-check

book-checks: $(STAMP)
	$(MAKE) --no-print-directory book
	$(MAKE) --no-print-directory check-book
	@if $(PY) -c 'import sys; from mechlib.pipeline.book.browser import find_browser; sys.exit(not find_browser())'; \
	then $(MAKE) --no-print-directory check-browser; \
	else echo "check-browser skipped: no Chromium on this machine (apt-get install chromium)"; fi
	@# the PDF, then its check (one after the other whatever job slots the caller has)
	@if $(PY) -m mechlib.pipeline.pdf tools; \
	then $(MAKE) --no-print-directory pdf && $(MAKE) --no-print-directory check-pdf; \
	else echo "pdf skipped: no Chromium or poppler-utils (apt-get install chromium poppler-utils)"; fi

determinism-check: $(STAMP)
	$(PIPELINE) determinism --records $(BUILD)/records --rerun $(RERUN)/records $(DETERMINISM_ARGS)

# --- the FE results store (store/) ----------------------------------------------------------------
# The pose-level results of the notebooks' FE runs, computed once (`make store`) and kept in the
# repository: `make test` seeds the build's FE cache from it (refusing a stale, edited or corrupt
# store in one line) and recomputes a sample of it cold, seeded by the commit.
STORE_LOG  := $(BUILD)/store-tasks.jsonl
# seeded once per store (again when store/ changes or the cache is removed); `make store-seed`
# seeds again whatever the stamp says
$(STORE_SEEDED): $(wildcard $(STORE)/manifest.json $(STORE)/results.npz $(STORE)/snapshots.npz) | $(STAMP)
	$(if $(NO_STORE_SEED),@echo "store: not read (make store FROM_EMPTY=1 solves every FE task)",\
	  $(PIPELINE) store seed --store $(STORE) --cache $(FE_CACHE) && touch $@)

store-seed: $(STAMP)
	$(PIPELINE) store seed --store $(STORE) --cache $(FE_CACHE)
	@mkdir -p $(FE_CACHE) && touch $(STORE_SEEDED)

store-check: $(STAMP)
	@if test -f $(STORE)/manifest.json; then $(PIPELINE) store check --store $(STORE); \
	else echo "store-check skipped: no $(STORE)/manifest.json (make store)"; fi

store: $(STAMP)
	$(REQUIRE_CI)
	$(PIPELINE) store clean
	$(if $(FROM_EMPTY),rm -rf $(BUILD)/cache/experiments)
	rm -rf $(BUILD)/executed $(STORE_LOG)
	@mkdir -p $(BUILD)
	start=$$(date +%s); head=$$(git rev-parse --short=12 HEAD); \
	MECHLIB_FE_LOG=$(abspath $(STORE_LOG)) $(if $(DASK_SCHEDULER),MECHLIB_DASK_SCHEDULER=$(DASK_SCHEDULER)) \
	  $(MAKE) --no-print-directory -j2 notebooks $(if $(FROM_EMPTY),NO_STORE_SEED=1); \
	$(PIPELINE) store pack --log $(STORE_LOG) --cache $(FE_CACHE) --store $(STORE) --commit $$head \
	  --seconds $$(( $$(date +%s) - start )) \
	  --workers "$(if $(DASK_SCHEDULER),Dask cluster $(DASK_SCHEDULER),the notebooks' local worker processes)" \
	  $(if $(FROM_EMPTY),--from-empty)

# every notebook executed again into $(RERUN), cold (an FE cache of its own) or, with
# FE_CACHE_FROM=<folder>, from a copy of that FE cache: `make test` requires its records to be
# byte-identical to the first run's, and recomputes a seeded sample of the cached FE tasks cold;
# with FIRST_RUN=<build folder>, each chapter takes its inputs from the first run's records (the
# comparison requires them identical to the re-run's) and none waits for another
rerun: $(STAMP)
	$(REQUIRE_CI)
	$(PIPELINE) rerun --out $(abspath $(RERUN)) $(if $(FE_CACHE_FROM),--fe-cache-from $(FE_CACHE_FROM)) \
	  $(if $(FIRST_RUN),--first-run $(FIRST_RUN))

# --- one notebook with new parameters ---------------------------------------------------------
run: $(STAMP) $(STORE_SEEDED)
	@test -n "$(NB)" || { echo "usage: make run NB=<notebook name> ARGS='-p name value ...'"; exit 2; }
	@test -f notebooks/$(NB).ipynb || { echo "no notebook notebooks/$(NB).ipynb; have: $(NB_NAMES)"; exit 2; }
	$(PIPELINE) run --notebook notebooks/$(NB).ipynb --out $(BUILD)/runs --records $(BUILD)/records \
	  -- $(ARGS)

references: $(EXECUTED)
	$(REQUIRE_CI)
	$(PIPELINE) update --records $(BUILD)/records --references tests/references

# the non-linear and chapter sections time the geometry the HexFlex notebook identifies (its
# record); without it they would fall back to the bench geometry, a different model
comma := ,
BENCH_ON_MODEL := $(if $(ONLY),$(filter nonlinear chapter reuse rom dask,$(subst $(comma), ,$(ONLY))),all)
bench: $(STAMP) $(if $(BENCH_ON_MODEL),$(BUILD)/executed/hexflex_model.ipynb)
	MECHLIB_RECORDS=$(abspath $(BUILD)/records) $(PY) -m mechlib.bench $(if $(ONLY),--only $(ONLY))

lint: $(STAMP)
	$(VENV)/bin/ruff check mechlib tests notebooks
	$(VENV)/bin/ruff format --check mechlib tests notebooks

clean:
	rm -rf $(BUILD) book/_build book/chapters book/generated book/report.md book/report_beyond.md book/intro.md

# --- PDF of the book --------------------------------------------------------------------------
# Headless Chromium prints the single-page HTML build after MathJax ran (from the build's own
# copy, network off); `check-pdf` compares the PDF with that HTML: page count, every page title,
# every raster figure, no formula left as TeX. Needs Debian's chromium and poppler-utils (.ci/run
# installs both). Run after `make book` (it reuses the generated pages; notebooks are not re-run).
PDF_HTML      := book/_build/singlehtml
PDF           := book/_build/pdf/book.pdf
# fewer pages than this means a truncated print (check-pdf also derives a floor from the amount
# of text; `pdfinfo book/_build/pdf/book.pdf` gives the page count of a build)
PDF_MIN_PAGES ?= 50
# more pages than this is a print that wastes paper: the book is read on paper in one go
PDF_MAX_PAGES ?= 130

.PHONY: pdf check-pdf
pdf: $(STAMP)
	@test -f book/_build/html/index.html || { echo "no HTML book: run make book first"; exit 2; }
	rm -rf $(PDF_HTML)
	$(VENV)/bin/jupyter-book build book --builder singlehtml -W -n --keep-going --quiet
	$(PY) -m mechlib.pipeline.pdf build --html $(PDF_HTML) --out $(PDF)

check-pdf: $(STAMP)
	$(PY) -m mechlib.pipeline.pdf check --pdf $(PDF) --html $(PDF_HTML) --min-pages $(PDF_MIN_PAGES) --max-pages $(PDF_MAX_PAGES)
