// libstratum_dependencies.so: no code, only libstratum.so's dependencies (DT_NEEDED, kept by
// --no-as-needed in CMakeLists.txt). The packaged add-on opens it before libstratum.so
// (addon/stratum/native/library.py): the dependencies load as one tree without deep binding,
// so that a library that uses a symbol of a sibling without naming it finds it in the tree's
// scope, as it does under libstratum.so, and everything binds malloc and free as the host does.
