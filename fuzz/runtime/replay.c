/*
 * replay.c - runs a harness without libFuzzer: feeds each file named on the command line to
 * LLVMFuzzerTestOneInput once. With -fsanitize=address,undefined -fno-sanitize-recover=all a
 * finding ends the program with a non-zero status; else it prints "replayed N inputs".
 */
#include <stdio.h>
#include <stdlib.h>

#include <stddef.h>
#include <stdint.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static unsigned char buf[1u << 20];

int main(int argc, char **argv)
{
    int i;
    for (i = 1; i < argc; i++) {
        size_t n;
        FILE *f = fopen(argv[i], "rb");
        if (f == NULL) {
            fprintf(stderr, "%s: cannot open\n", argv[i]);
            return 2;
        }
        n = fread(buf, 1, sizeof buf, f);
        fclose(f);
        fprintf(stderr, "%s\n", argv[i]);
        (void)LLVMFuzzerTestOneInput(buf, n);
    }
    printf("replayed %d inputs\n", argc - 1);
    return 0;
}
