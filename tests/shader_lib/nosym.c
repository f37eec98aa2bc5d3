/* nosym.c - a shared object that is no shader library: it lacks sgapi_shader_library. */
int sg_test_not_a_library(void);

int sg_test_not_a_library(void) {
    return 42;
}
