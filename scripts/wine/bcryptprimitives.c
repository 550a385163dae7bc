/* A stand-in for Windows' bcryptprimitives.dll, which wine 8 lacks and
 * Rust's standard library asks for (ProcessPrng, its source of random
 * bytes): the same bytes from RtlGenRandom (advapi32's SystemFunction036),
 * which wine has. Built with mingw-w64 by scripts/wine.sh, for running the
 * Windows program under wine in CI; never shipped. */
#include <windows.h>

BOOLEAN WINAPI SystemFunction036(PVOID buffer, ULONG length);

__declspec(dllexport) BOOL WINAPI ProcessPrng(PBYTE data, SIZE_T length)
{
    while (length > 0) {
        ULONG n = length > 0x40000000 ? 0x40000000 : (ULONG)length;
        if (!SystemFunction036(data, n))
            return FALSE;
        data += n;
        length -= n;
    }
    return TRUE;
}
