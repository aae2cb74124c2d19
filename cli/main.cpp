#include "commands.h"

int main(int argc, char **argv) {
    return aaf::cli::run(argc, argv);
}
