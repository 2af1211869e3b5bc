/* paper_images_driver.c - runs the Tables 6-7 experiment as `abrdf tables 6|7` will:
 * paper_images_driver 6|7 [options]. */
#include "paper_images.h"

int main(int argc, char **argv) { return paper_images_cmd(argc - 1, argv + 1); }
