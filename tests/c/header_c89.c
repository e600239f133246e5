/* The header compiles as strict C89 (issue 16, item 15): no comma after an enum's last
 * enumerator, no C++ comments. Compiled by ctest with -std=c89 -pedantic-errors. */
#include "intrinsym.h"
int header_c89(void) { return SYM_ABI_VERSION == 1 && SYM_STATUS_OK == 0 && SYM_KIND_PARTIAL == 1; }
