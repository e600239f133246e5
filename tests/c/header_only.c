/* The header compiles alone (as C11 here, as C++17 in header_only.cpp). */
#include "intrinsym.h"
int header_only_c(void) { return SYM_ABI_VERSION == 1 && SYM_STATUS_OK == 0; }
