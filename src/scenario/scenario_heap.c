/* rockdem — scenarios on the heap, for bindings that cannot size rd_scenario themselves (the
 * Python module tools/rockdem calls these through ctypes).
 * Folder scenario/ owns the scenario language (parse, --set overrides, validation); it may call
 * base/, records/ and geometry/, never engine/, io/ or cli/.
 */
#include "rockdem/scenario.h"

#include <stdlib.h>

rd_scenario *rd_scenario_new(void)
{
    rd_scenario *sc = malloc(sizeof *sc);
    if (sc) rd_scenario_defaults(sc);
    return sc;
}

void rd_scenario_delete(rd_scenario *sc)
{
    if (!sc) return;
    rd_scenario_free(sc);
    free(sc);
}
