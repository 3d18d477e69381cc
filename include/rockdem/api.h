/* rockdem — RD_API marks the functions librockdem exports. The library is compiled with
 * -fvisibility=hidden, so everything else (the folders' shared helpers) stays inside it, in the
 * shared library and, through `objcopy --localize-hidden`, in the static one as well. A program
 * linking librockdem sees exactly the functions declared in include/rockdem/.
 */
#ifndef ROCKDEM_API_H
#define ROCKDEM_API_H

#if defined(__GNUC__)
#define RD_API __attribute__((visibility("default")))
#else
#define RD_API
#endif

#endif
