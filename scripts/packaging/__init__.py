"""`make package` (package.py): the zip users install, the libraries it bundles under private
names (library_bundle.py, elf_names.py) and their licences (third_party_notices.py); and
copy_oidn.py, which `make build` runs to put Open Image Denoise beside libstratum.so in
addon/stratum/lib."""
