"""The repository's tools, one room (package) per role. A module runs from the repository's
root as `python -m scripts.<room>.<module>` (the venv's Python, with the bpy wheel where it
needs Blender), or inside Blender through scripts/run_in_blender.py; none changes sys.path.

| room                         | role                                                             |
|------------------------------|------------------------------------------------------------------|
| setup.sh, requirements.txt   | the machine: Debian packages and the project's .venv             |
| install_addon.sh             | this checkout's add-on linked into Blender's user add-on folder  |
| run_in_blender.py            | the one launcher Blender runs this package's modules with        |
| settings_table.py            | the README's render-settings tables (`make settings-table`)      |
| packaging/                   | `make package`: the zip, its private libraries and their         |
|                              | licences; Open Image Denoise copied into addon/stratum/lib       |
| render/                      | `make render` and `make profile`: a .blend rendered or captured  |
| bench/                       | `make bench`: Stratum against Cycles, speed, quality and memory  |
| study/                       | `make study`: the sampler, estimator, light, adaptive, radiosity |
|                              | and guiding studies, their summary and figures                   |
| cycles_reference/            | Cycles measured: the reference values tests hold                 |

The fuzzer's corpus assembler, runner and triage live beside it, in native/fuzz/tools/.
"""

from pathlib import Path

REPO = Path(__file__).resolve().parent.parent  # the checkout every tool reads and writes under
