/*
 * The end of a call of the compiled extensions (_band.c, _multiword.c): every buffer it
 * took released, then None, or the error its arguments earned. One place for what each
 * call would otherwise repeat.
 */
#ifndef SYMTMM_BUFFERS_H
#define SYMTMM_BUFFERS_H

#include <Python.h>

/* The outcomes a call reports through released(). */
enum { CALL_DONE = 1, CALL_MISFIT = 0, CALL_NO_MEMORY = -1 };

/* Releases the buffers of `buffers` (NULL ends the list); returns None for CALL_DONE,
 * raises ValueError(`message`) for CALL_MISFIT (buffers or tables that do not fit) and
 * MemoryError for CALL_NO_MEMORY. */
static PyObject *released(int outcome, const char *message, Py_buffer *const *buffers)
{
    for (; *buffers != NULL; buffers++)
        PyBuffer_Release(*buffers);
    if (outcome == CALL_NO_MEMORY)
        return PyErr_NoMemory();
    if (outcome != CALL_DONE) {
        PyErr_SetString(PyExc_ValueError, message);
        return NULL;
    }
    Py_RETURN_NONE;
}

/* RELEASED(outcome, message, &a, &b, ...): released() over the buffers listed. */
#define RELEASED(outcome, message, ...) \
    released((outcome), (message), (Py_buffer *const[]){__VA_ARGS__, NULL})

#endif
