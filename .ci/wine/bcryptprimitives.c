/*
 * A stand-in for Windows' bcryptprimitives.dll, for running our Windows build under
 * Wine 8 (Debian 12's wine64), which lacks the DLL. Rust's std (1.78 and later) takes
 * its random bytes (HashMap's keys) from ProcessPrng, which that DLL exports; without
 * it the exe does not start. Real Windows 10 and later have the DLL: this is for CI
 * under Wine only and is never shipped.
 *
 * ProcessPrng fills the buffer from RtlGenRandom (advapi32's SystemFunction036), the
 * generator Rust's std used before 1.78. Built by .ci/wine/setup with mingw-w64.
 */
#include <windows.h>

BOOLEAN WINAPI SystemFunction036(PVOID buffer, ULONG length);

BOOL WINAPI ProcessPrng(PBYTE data, SIZE_T length)
{
    /* RtlGenRandom takes a ULONG: fill a longer buffer in pieces. */
    while (length > 0) {
        ULONG piece = length > 0x40000000 ? 0x40000000 : (ULONG)length;
        if (!SystemFunction036(data, piece))
            return FALSE;
        data += piece;
        length -= piece;
    }
    return TRUE;
}
