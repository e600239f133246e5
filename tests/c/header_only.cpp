// The header compiles alone as C++17 and links from C++.
#include "intrinsym.h"
#include <cstdio>
extern "C" int header_only_c(void);
int main() {
    sym_params *p = sym_params_new();
    sym_params_free(p);
    std::printf("header_only: C %d, C++ ok, version %s\n", header_only_c(), sym_version());
    return header_only_c() ? 0 : 1;
}
