# partscene: `make test` and `make demo` set up everything on a fresh Debian machine (Python >= 3.11).
PYTHON ?= python3
VENV   ?= .venv
PY     := $(VENV)/bin/python
STAMP  := $(VENV)/.partscene-installed
JOBS   ?= 2

.PHONY: setup test demo bench clean

setup: $(STAMP)

$(STAMP): pyproject.toml .ci/system-deps
	PYTHON=$(PYTHON) ./.ci/system-deps
	$(PYTHON) -c 'import sys; assert sys.version_info >= (3, 11), "partscene needs Python >= 3.11, found " + sys.version'
	test -x $(PY) || $(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e '.[test]'
	$(PY) -c 'import open3d, pybullet, pinocchio, ompl, trimesh, yourdfpy' \
	  || { echo "partscene: the installed packages do not import (see the error above)" >&2; exit 1; }
	touch $(STAMP)

# one thread per test worker: BLAS (and open3d < 0.20, OpenMP) reductions then sum in one order, so a recon
# decision on a borderline value does not depend on the load
test: setup
	OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 MKL_NUM_THREADS=1 $(PY) -m pytest -n $(JOBS) -q

demo: setup
	$(PY) -m simcheck.demo --out out/demo

bench: setup
	$(PY) -m bench

clean:
	rm -rf $(VENV) out build *.egg-info
