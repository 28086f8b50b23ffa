#!/usr/bin/env bash
# The environment of one student's Jupyter server on a hub or on Binder, then the server.
# Used by all three recipes: deploy/jupyterhub/jupyterhub_config.py (Spawner.cmd), the
# Zero to JupyterHub image (deploy/z2jh/Dockerfile, ENTRYPOINT) and binder/start.
# Usage: singleuser-start.sh jupyterhub-singleuser [ARGS...]
#
# These are `make lab`'s live settings for a Linux server without a screen (see the
# Makefile and docs/headless.md), plus what a hub needs:
# - VTK_DEFAULT_OPENGL_WINDOW: render with EGL, there is no X server.
# - VTK_WASM_DIR_OVERRIDE: an empty folder, so trame-vtklocal never tries to download VTK.wasm.
# - PYVISTA_TRAME_SERVER_PROXY_PREFIX: the live 3D views reach the kernel's trame server
#   through jupyter-server-proxy under this user's own prefix (/user/NAME/proxy/PORT).
#   pyvista puts $JUPYTERHUB_SERVICE_PREFIX (/user/NAME/) in front by itself, so the
#   variable is only "/proxy/": with the prefix in it too, the view's address had it
#   twice (/user/NAME/user/NAME/proxy/...) and the live view stayed an error page.
# PYVISTA_JUPYTER_BACKEND=static is NOT set: that is for CI only and would turn every live
# view into a picture. A hub short of memory may set HALFEDGE_EDU_VIZ=static instead.
#
# Memory and CPU of each student's kernel (issue 14; a value already set wins):
# - HALFEDGE_EDU_LIVE_BACKEND=client: the live 3D views are drawn by vtk.js in the
#   browser, so the kernel keeps no render window per widget and rotating costs it
#   nothing. Labels are not drawn in that view and vertices are squares; a hub that
#   wants them sets HALFEDGE_EDU_LIVE_BACKEND=server (jupyterhub_config.py passes it on).
# - MALLOC_MMAP_THRESHOLD_ and MALLOC_TRIM_THRESHOLD_ (glibc): blocks of 128 KiB and more
#   go back to the system when freed (a closed scene's render window, a step's
#   temporary arrays) instead of staying in the kernel's heap; 20-25 MiB less per
#   kernel after chapter 03, measured.
# - LP_NUM_THREADS: Mesa's software renderer starts one thread per core of the machine,
#   each with its own buffers; a student has one CPU (the spawner's cpu_limit).
set -euo pipefail

export VTK_DEFAULT_OPENGL_WINDOW=vtkEGLRenderWindow
export VTK_WASM_DIR_OVERRIDE="${VTK_WASM_DIR_OVERRIDE:-$HOME/.cache/halfedge_edu/vtk-wasm-empty}"
export PYVISTA_TRAME_SERVER_PROXY_PREFIX="/proxy/"
export HALFEDGE_EDU_LIVE_BACKEND="${HALFEDGE_EDU_LIVE_BACKEND:-client}"
export MALLOC_MMAP_THRESHOLD_="${MALLOC_MMAP_THRESHOLD_:-131072}"
export MALLOC_TRIM_THRESHOLD_="${MALLOC_TRIM_THRESHOLD_:-131072}"
export LP_NUM_THREADS="${LP_NUM_THREADS:-1}"
mkdir -p "$VTK_WASM_DIR_OVERRIDE"
# The kernels' Unix sockets (the hub starts servers with --KernelManager.transport=ipc) live
# in the runtime folder, by default under the home: a long home path
# (/var/lib/private/firstname.lastname/.local/share/jupyter/runtime/kernel-UUID-ipc-1)
# passes the 107 bytes a socket path may have, and every kernel fails to start ("File name
# too long"). A fresh private folder under /tmp for each server start is short enough.
if [ -z "${JUPYTER_RUNTIME_DIR:-}" ]; then
  JUPYTER_RUNTIME_DIR="$(mktemp -d /tmp/jr-XXXXXXXX)"
  export JUPYTER_RUNTIME_DIR
fi

# Each student's own copy of the chapters, from the installed package; a chapter the
# student edited is never overwritten. --update: after the hub's package (or image) is
# updated, errata reach every student at their next server start; an edited chapter is
# kept and the newer one written beside it (NN_topic-VERSION.ipynb). A failure here must
# not keep the server from starting.
halfedge-edu course "${HALFEDGE_EDU_COURSE_DIR:-$HOME/course}" --update || echo "singleuser-start: could not copy the whole course" >&2

exec "$@"
