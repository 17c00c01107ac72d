/* view/job.c — the thread of a background job of the viewer (the reference render, a material build):
 * started, polled, joined, or abandoned (then the worker frees the job when it ends). */
#include "view/view_internal.h"

static void *trampoline(void *arg)
{
    view_job *j = arg;
    j->run(j);
    pthread_mutex_lock(&j->lock);
    j->done = 1;
    int abandoned = j->abandoned;
    pthread_mutex_unlock(&j->lock);
    if (abandoned) j->free(j); /* nobody will join: the thread was detached */
    return NULL;
}

sss_result view_job_init(view_job *j, void (*run)(view_job *), void (*free_job)(view_job *), sss_error *err)
{
    j->run = run;
    j->free = free_job;
    if (pthread_mutex_init(&j->lock, NULL) != 0)
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "cannot create a mutex for a background job");
    j->lock_ready = 1;
    return SSS_OK;
}

sss_result view_job_start(view_job *j, sss_error *err)
{
    if (pthread_create(&j->thread, NULL, trampoline, j) != 0)
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "cannot start a background thread");
    return SSS_OK;
}

int view_job_done(view_job *j)
{
    pthread_mutex_lock(&j->lock);
    int done = j->done;
    pthread_mutex_unlock(&j->lock);
    return done;
}

void view_job_join(view_job *j) { pthread_join(j->thread, NULL); }

void view_job_abandon(view_job *j)
{
    pthread_mutex_lock(&j->lock);
    int done = j->done;
    j->abandoned = 1;
    pthread_mutex_unlock(&j->lock);
    if (done) {
        pthread_join(j->thread, NULL);
        j->free(j);
    } else {
        pthread_detach(j->thread);
    }
}

void view_job_destroy(view_job *j)
{
    if (j->lock_ready) pthread_mutex_destroy(&j->lock);
    j->lock_ready = 0;
}
